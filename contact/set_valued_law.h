// What the event core asks of a set-valued (dry) friction law (eq. frictionlaw and its static
// generalisation): its bounds and the one place that decides stick and slip, for both engines
// and the event resolver (sim/events/). A law's engine form (contact/platform_friction.h) carries
// one; the force while slipping is the law's own (PlatformFriction::force: -kinetic_bound *
// sign(v) for Coulomb's law, a function of the speed for others).
//   sticking (v == 0):  F takes whatever value keeps the platform still, while |F| < static_bound;
//                       once the force needed reaches the static bound, the platform slips in the
//                       direction the other forces push it, with the slip force opposing.
// Coulomb's law has static_bound == kinetic_bound; static friction above kinetic has
// static_bound > kinetic_bound (a slip that stops under a push between the two bounds sticks).
// The tie |holding force| == static_bound breaks free, in every decision below (canHold,
// modeAtRest, breaksFree are one rule): at a located stick -> slip event the margin is zero to
// rounding, and a platform left stuck at margin 0 would never see its witness cross again.
// Units are the caller's: bounds = mu-bar M g (newtons) or mu (scaled).
#pragma once

#include "contact/platform_mode.h"

namespace metrosync {

class SetValuedLaw {
 public:
  SetValuedLaw() = default;
  // static_bound >= kinetic_bound >= 0 (the law values check it; contact/friction_law.h)
  SetValuedLaw(double static_bound, double kinetic_bound)
      : static_bound_(static_bound), kinetic_bound_(kinetic_bound) {}
  // Coulomb's law: one bound for holding and slipping.
  static SetValuedLaw coulomb(double bound) { return SetValuedLaw(bound, bound); }

  double staticBound() const { return static_bound_; }
  double kineticBound() const { return kinetic_bound_; }

  // Can friction supply `holding_force` (the force that keeps the platform still)? Strictly
  // inside the static bound only: the tie breaks free. NaN is never held.
  bool canHold(double holding_force) const {
    return holding_force < static_bound_ && holding_force > -static_bound_;
  }

  // A stuck platform breaks free exactly when friction cannot hold it. Below the bound it stays:
  // a slip could not start, the platform would accelerate against its own direction of slip.
  bool breaksFree(double holding_force) const { return !canHold(holding_force); }

  // The direction of a slip that starts from rest: holding_force > 0 means friction would have
  // to push in +x, i.e. the other forces push the platform towards -x.
  static PlatformMode slipDirection(double holding_force) {
    return holding_force > 0 ? PlatformMode::SlipNegative : PlatformMode::SlipPositive;
  }

  // The mode of a platform at rest (xdot == 0 exactly): stuck if friction can hold it, otherwise
  // sliding the way the other forces push it.
  PlatformMode modeAtRest(double holding_force) const {
    return canHold(holding_force) ? PlatformMode::Stuck : slipDirection(holding_force);
  }

  // The mode of a platform moving at v: a slip in its direction; at v == 0 exactly, modeAtRest.
  PlatformMode modeAt(double v, double holding_force) const {
    if (v > 0) return PlatformMode::SlipPositive;
    if (v < 0) return PlatformMode::SlipNegative;
    return modeAtRest(holding_force);
  }

  // Stick -> slip witness: positive while the platform can stay stuck, reaches zero when the
  // needed holding force reaches the static bound in either direction (falling: it breaks free).
  double stickMargin(double holding_force) const {
    return static_bound_ - (holding_force >= 0 ? holding_force : -holding_force);
  }

 private:
  double static_bound_ = 0.0;   // largest holding force, >= kinetic_bound_
  double kinetic_bound_ = 0.0;  // Coulomb's slip force's magnitude (of a speed-dependent law: its
                                // limit at high speed), >= 0
};

}  // namespace metrosync
