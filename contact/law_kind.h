// What one friction law defines (one file per law in contact/, one line in
// contact/law_registry.h): its rig-file name and keys (with defaults), each parameter's unit (how
// it scales), its rules across parameters, the engines' form at a normal force with its force
// and derivatives, and its averaged response for the slow flow or why it has none. The law value
// (contact/friction_law.h) pairs a kind with its parameter values; everything generic (reading,
// --set keys, JSON, scaling, comparison) runs over parameters(), so a new parameter is seen
// everywhere at once, and everything the engines and analyses ask goes through
// PlatformFriction (contact/platform_friction.h) and SlowResponse (contact/slow_response.h), so
// no code outside contact/ asks which law it is (tests/layout checks it).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "contact/platform_friction.h"
#include "contact/slow_response.h"

namespace metrosync {

// A parameter's unit as powers of the rig's scales (models/scaling.h, LawScales): its scaled
// value is physical / (eps^{3/2})^coefficient M^mass x_scale^length omega0^rate.
struct LawUnit {
  int coefficient = 0;    // a friction coefficient (mu = mu-bar / eps^{3/2})
  int mass = 0;           // kg: M, the platform with everything on it
  int length = 0;         // m: the platform's length scale x_scale
  int rate = 0;           // 1/s: omega0
  const char* text = "";  // the physical unit as `metrosync scale` writes it ("" for a number)
};
constexpr LawUnit kFrictionCoefficient{1, 0, 0, 0, ""};
constexpr LawUnit kDampingCoefficient{0, 1, 0, 1, "N s/m"};  // c = c-bar / (M omega0)
constexpr LawUnit kVelocity{0, 0, 1, 1, "m/s"};              // V = V-bar / (x_scale omega0)
constexpr LawUnit kPureNumber{};                             // not scaled (an exponent)

struct LawParameter {
  const char* key;  // under platform.friction in a rig file
  LawUnit unit;
  const char* physical_help;  // what it is, for a message about a physical rig
  const char* scaled_help;    // the same for a scaled rig
  // the value when the rig file leaves the key out, in the rig's units (nullopt: the key is
  // required); a default of a pure number (kPureNumber) means the same in physical and scaled rigs
  std::optional<double> fallback = std::nullopt;
};

// A rule across parameters (e.g. mu_static >= mu): the key at fault and what is wrong.
struct LawViolation {
  std::string key;
  std::string why;
};

class LawKind : public SlipLaw {
 public:
  virtual ~LawKind() = default;
  virtual const char* name() const = 0;  // platform.friction.law
  // Every parameter (at most kMaxLawParameters); values follow this order.
  virtual const std::vector<LawParameter>& parameters() const = 0;
  // Rules beyond each value >= 0 (which the reader checks); nullopt when they hold.
  virtual std::optional<LawViolation> check(const std::vector<double>&) const {
    return std::nullopt;
  }

  // --- the engines' form ----------------------------------------------------------------------
  // The law at normal force N (its traits, and a set-valued law's bounds: coefficients times N;
  // the units are the caller's). Made with `constants(values, N)`. Its force and derivatives are
  // the SlipLaw functions above (contact/platform_friction.h), which PlatformFriction calls (a
  // constant slip force it computes itself).
  virtual PlatformFriction platform(const std::vector<double>& values, double N) const = 0;

  // --- the analyses ---------------------------------------------------------------------------
  // The slow flow's view, values in scaled units.
  virtual SlowResponse slowResponse(const std::vector<double>& values) const = 0;
  // Can the law keep the platform still under a sinusoidal push of amplitude `drive` (scaled)?
  // The slow flow's regime labels a platform by this (sim/analysis/regime.h).
  virtual bool holdsDrive(const std::vector<double>& values, double drive) const = 0;
  // The coefficient mu of Coulomb's law when the law is that law (one bound for holding and
  // slipping, a slip force independent of the speed), for what only Coulomb's law has: the bench's
  // peers, the paper's section-3A measurement. nullopt otherwise.
  virtual std::optional<double> coulombCoefficient(const std::vector<double>&) const {
    return std::nullopt;
  }
  // The effective scaled mu of a law without parameters, reported by `metrosync scale` (none: 0,
  // fixed: infinite, i.e. null); nullopt for a law whose parameters say it all.
  virtual std::optional<double> reportedMu() const { return std::nullopt; }

 protected:
  // The constants a PlatformFriction of this law is evaluated at.
  static LawConstants constants(const std::vector<double>& values, double N) {
    LawConstants k;
    for (std::size_t i = 0; i < values.size() && i < k.values.size(); ++i) k.values[i] = values[i];
    k.normal_force = N;
    return k;
  }
};

}  // namespace metrosync
