// Coulomb (dry) friction on the platform as a small value type (eq. frictionlaw): the one place
// that decides stick and slip, for both engines and the slow flow's switches.
//   slipping (v != 0):  F = -bound * sign(v)
//   sticking (v == 0):  F takes whatever value keeps the platform still, while |F| < bound;
//                       once the force needed reaches the bound, the platform slips in the
//                       direction the other forces push it, with friction F = +-bound opposing.
// The tie |holding force| == bound breaks free, in every decision below (canHold, modeAtRest,
// breaksFree are one rule): at a located stick -> slip event the margin is zero to rounding, and
// a platform left stuck at margin 0 would never see its witness cross again.
// Units are the caller's: bound = mu-bar M g (newtons) or mu (scaled).
#pragma once

#include "contact/friction_law.h"

namespace metrosync {

struct CoulombLaw {
  double bound = 0.0;  // maximum magnitude of the friction force, >= 0

  // mu-bar M g (eq. frictionlaw): the bound from the coefficient and the normal force, computed
  // here once for every engine.
  static CoulombLaw fromCoefficient(double mu, double normal_force) {
    return CoulombLaw{mu * normal_force};
  }

  // Friction force while slipping in `mode` (0 when stuck: the holding force is a constraint).
  double slipForce(PlatformMode mode) const { return -bound * static_cast<int>(mode); }

  // Can friction supply `holding_force` (the force that keeps the platform still)? Strictly
  // inside the bound only: the tie breaks free. NaN is never held.
  bool canHold(double holding_force) const {
    return holding_force < bound && holding_force > -bound;
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
  // needed holding force reaches the bound in either direction (falling: it breaks free).
  double stickMargin(double holding_force) const {
    return bound - (holding_force >= 0 ? holding_force : -holding_force);
  }
};

// Viscous platform friction F = -c v (the earlier models' law).
struct ViscousLaw {
  double c = 0.0;
  double force(double v) const { return -c * v; }
};

}  // namespace metrosync
