// What one friction law defines (one file per law in contact/, one line in
// contact/law_registry.cpp): its rig-file name and keys, how each parameter scales, what the
// engines get at a normal force, and its averaged response for the slow flow where one exists.
// The law value (contact/friction_law.h) pairs a kind with its parameter values; everything
// generic (reading, --set keys, JSON, scaling, comparison) runs over parameters(), so a new
// parameter is seen everywhere at once.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "contact/averaged_response.h"
#include "contact/platform_friction.h"

namespace metrosync {

// How a parameter goes from physical to scaled units (models/scaling.h):
//   Coefficient  a friction coefficient: mu = mu-bar / eps^{3/2}
//   Viscous      a damping coefficient:  c = c-bar / (M omega0)
enum class LawScale { Coefficient, Viscous };

struct LawParameter {
  const char* key;  // under platform.friction in a rig file
  LawScale scale;
  const char* physical_help;  // what it is, for a message about a physical rig
  const char* scaled_help;    // the same for a scaled rig
};

// The slow flow's view of a law (contact/averaged_response.h, models/slow_flow.h):
//   None      no averaged response derived: the slow flow refuses the law (`why` says so)
//   Constant  beta independent of the drive amplitude (viscous, none, fixed, Coulomb mu = 0)
//   Coulomb   eq. d2 at s = A / mu, mu > 0, with its stuck/stick-slip/slip switches
struct SlowResponse {
  enum class Kind { None, Constant, Coulomb };
  Kind kind = Kind::None;
  AveragedResponse constant;  // Constant
  double mu = 0.0;            // Coulomb
  std::string why;            // None: why there is none, for the message

  // The response at drive amplitude A >= 0 (Coulomb: coulombResponse(A / mu)); throws
  // std::invalid_argument for Kind::None.
  AveragedResponse at(double A) const;
};

// Coulomb's law's view at coefficient mu (contact/coulomb.cpp): Constant (1/2, 0) at mu = 0,
// else Coulomb.
SlowResponse coulombSlowResponse(double mu);

// A rule across parameters (e.g. mu_static >= mu): the key at fault and what is wrong.
struct LawViolation {
  std::string key;
  std::string why;
};

class LawKind {
 public:
  virtual ~LawKind() = default;
  virtual const char* name() const = 0;  // platform.friction.law
  // Every parameter, each required in a rig file; values follow this order.
  virtual const std::vector<LawParameter>& parameters() const = 0;
  // Rules beyond each value >= 0 (which the reader checks); nullopt when they hold.
  virtual std::optional<LawViolation> check(const std::vector<double>&) const {
    return std::nullopt;
  }
  // The engines' law at `normal_force` (the bounds of a set-valued law are coefficient times
  // normal force; the units are the caller's).
  virtual PlatformFriction platform(const std::vector<double>& values,
                                    double normal_force) const = 0;
  // The slow flow's view, values in scaled units.
  virtual SlowResponse slowResponse(const std::vector<double>& values) const = 0;
  // Can the law keep the platform still under a sinusoidal push of amplitude `drive` (scaled)?
  // The slow flow's regime labels a platform by this (sim/analysis/regime.h).
  virtual bool holdsDrive(const std::vector<double>& values, double drive) const = 0;
  // The effective scaled mu of a law without parameters, reported by `metrosync scale` (none: 0,
  // fixed: infinite, i.e. null); nullopt for a law whose parameters say it all.
  virtual std::optional<double> reportedMu() const { return std::nullopt; }
};

}  // namespace metrosync
