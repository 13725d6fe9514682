// Coulomb (dry) friction on the platform as a small value type (eq. frictionlaw):
//   slipping (v != 0):  F = -bound * sign(v)
//   sticking (v == 0):  F takes whatever value keeps the platform still, while |F| <= bound;
//                       once the force needed exceeds the bound, the platform slips in the
//                       direction the other forces push it, with friction F = +-bound opposing.
// Units are the caller's: bound = mu-bar M g (newtons) or mu (scaled).
#pragma once

#include "contact/friction_law.h"

namespace metrosync {

struct CoulombLaw {
  double bound = 0.0;  // maximum magnitude of the friction force, >= 0

  // Friction force while slipping in `mode` (0 when stuck: the holding force is a constraint).
  double slipForce(PlatformMode mode) const { return -bound * static_cast<int>(mode); }

  // Can friction supply `holding_force` (the force that keeps the platform still)?
  bool canHold(double holding_force) const {
    return holding_force <= bound && holding_force >= -bound;
  }

  // The mode after the platform stops or ticks: stuck if the needed holding force fits in the
  // bound, otherwise sliding against it. holding_force > 0 means friction would have to push in
  // +x, i.e. the other forces push the platform towards -x.
  PlatformMode modeAtRest(double holding_force) const {
    if (canHold(holding_force)) return PlatformMode::Stuck;
    return holding_force > 0 ? PlatformMode::SlipNegative : PlatformMode::SlipPositive;
  }

  // A stuck platform breaks free once the force needed to hold it reaches the bound (a tie breaks
  // free: at a located stick -> slip event the margin is zero to rounding, and a platform left
  // stuck at margin 0 would never see its witness cross again). Below the bound it stays: a slip
  // could not start, the platform would accelerate against its own direction of slip.
  bool breaksFree(double holding_force) const {
    return !(holding_force < bound && holding_force > -bound);
  }

  // Stick -> slip witness: positive while the platform can stay stuck, crosses zero when the
  // needed holding force reaches the bound in either direction.
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
