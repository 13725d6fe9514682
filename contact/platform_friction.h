// A friction law at a normal force, as the engines and the analyses ask it (newtons, or scaled
// units: the caller's): the force at a slip velocity in a mode, its derivatives (in the slip
// velocity, in each of the law's parameters and the normal force), the stick/slip bounds of a
// set-valued law (contact/set_valued_law.h) and what the platform can do (move, stick, feel a
// force). A law's file (contact/*.cpp, LawKind::platform) makes one; the direct engine
// (models/platform_arrow.cpp, models/network_equations.cpp), the event resolver (sim/events/),
// the Simbody elements (contact/simbody/), the periodic-orbit Jacobians and the bench's peers ask
// it, never which law it is.
//
// The force of a set-valued law whose slip force does not depend on the speed (Coulomb's law and
// its static variant) is computed here inline, -kinetic bound * mode: the direct engine's hot
// path. Every other force is the law's own function (SlipLaw::force), called through its kind.
#pragma once

#include <array>

#include "contact/platform_mode.h"
#include "contact/set_valued_law.h"

namespace metrosync {

// The most parameters a law may have (LawKind::parameters()).
constexpr int kMaxLawParameters = 4;

// What a law's functions are evaluated at: its parameter values (in FrictionLaw::values()'s
// order and units) and the normal force N on the contact.
struct LawConstants {
  std::array<double, kMaxLawParameters> values{};
  double normal_force = 0.0;
};

// The derivative of a quantity (the force, the static bound) in each of the law's parameter
// values (FrictionLaw::values()'s order and units; entries beyond the law's count are 0) and in
// the normal force.
struct LawGradient {
  std::array<double, kMaxLawParameters> values{};
  double normal_force = 0.0;
};

// A law's force as the engines call it: the functions every law defines (LawKind derives from
// this, contact/law_kind.h; PlatformFriction calls them at its constants).
class SlipLaw {
 public:
  // The force at slip velocity v in `mode` (0 while stuck: the holding force is a constraint),
  // its derivative in v, in each parameter value and in N.
  virtual double force(const LawConstants& k, double v, PlatformMode mode) const = 0;
  virtual double forceSlope(const LawConstants& k, double v, PlatformMode mode) const = 0;
  virtual LawGradient forceGradient(const LawConstants& k, double v, PlatformMode mode) const = 0;
  // d(static bound)/d(values, N) of a set-valued law; zero for the others.
  virtual LawGradient staticBoundGradient(const LawConstants&) const { return {}; }

 protected:
  ~SlipLaw() = default;
};

// What a law says of the platform it acts on (LawKind::platform sets them).
struct LawTraits {
  bool moves = true;           // false: the platform is bolted to the table (fixed)
  bool set_valued = false;     // stuck below a bound at zero slip velocity (stick/slip modes)
  bool exerts_force = false;   // a force while the platform moves (else none at all)
  bool constant_slip = false;  // set-valued with slip force -kinetic bound * mode at any speed
};

class PlatformFriction {
 public:
  // No friction at all (a free platform).
  PlatformFriction() = default;
  // `law` evaluated at `constants`; `bounds` for a set-valued law (static >= kinetic >= 0).
  PlatformFriction(const SlipLaw& law, const LawConstants& constants, LawTraits traits,
                   SetValuedLaw bounds = {})
      : law_(&law), constants_(constants), traits_(traits), bounds_(bounds) {}

  // Stuck below a bound at zero slip velocity (the engines keep a mode and locate stick/slip
  // events); the other laws are smooth forces of the velocity.
  bool setValued() const { return traits_.set_valued; }
  // The platform can move at all (not bolted to the table).
  bool platformMoves() const { return traits_.moves; }
  // A moving platform feels a force (false: no friction, the Simbody assembly adds no element).
  bool exertsForce() const { return traits_.exerts_force; }
  // Set-valued with a slip force of constant size, the kinetic bound (Coulomb's law; the bench's
  // peers implement this one).
  bool constantSlipForce() const { return traits_.constant_slip; }
  // The stick/slip bounds and decisions (setValued() only).
  const SetValuedLaw& bounds() const { return bounds_; }
  const LawConstants& constants() const { return constants_; }

  // The friction force on a platform slipping at v in `mode` (mode matters for a set-valued law
  // only: its slip force in that direction while slipping, 0 while stuck, where the holding
  // force is a constraint).
  double force(double v, PlatformMode mode) const {
    if (traits_.constant_slip) return -bounds_.kineticBound() * static_cast<int>(mode);
    return lawForce(v, mode);
  }
  // Power taken out of the system (>= 0 for a dissipative law): -F v.
  double power(double v, PlatformMode mode) const { return -force(v, mode) * v; }
  // dF/dv at v in `mode` (0 while stuck and for a constant slip force).
  double forceSlope(double v, PlatformMode mode) const;
  // dF/d(each parameter value) and dF/dN at v in `mode` (0 while stuck): the fit's variational
  // equations (issue 36) and any sensitivity of a run to the law.
  LawGradient forceGradient(double v, PlatformMode mode) const;
  // d(static bound)/d(each parameter value) and d/dN (set-valued laws; 0 for the others): how a
  // stick -> slip event moves with the law.
  LawGradient staticBoundGradient() const;

 private:
  double lawForce(double v, PlatformMode mode) const;  // the law's own force (out of line)

  const SlipLaw* law_ = nullptr;  // nullptr: no friction
  LawConstants constants_;
  LawTraits traits_;
  SetValuedLaw bounds_;
};

}  // namespace metrosync
