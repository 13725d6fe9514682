// What a friction law contributes to the derivatives of a trajectory (the fit's exact Jacobian,
// sim/analysis/fit/; the linearizations of sim/analysis/periodic_orbit/): how the force the
// platform feels in a mode changes with its slip velocity, with each of the law's own parameters
// (FrictionLaw::values()) and with the normal force, and how the static bound -- the largest
// holding force, where a stuck platform breaks free -- changes with the same parameters.
// Everything law-dependent that those derivatives need is here, beside the laws (one function:
// the law interface of issue 38 takes it over as one method per law).
#pragma once

#include <vector>

#include "contact/friction_law.h"
#include "contact/platform_mode.h"

namespace metrosync {

struct FrictionPartials {
  double force_per_velocity = 0.0;      // dF/dv in the mode
  double force_per_normal_force = 0.0;  // dF/dN
  std::vector<double> force_per_value;  // dF/d values()[i], (values x 1)
  // the static bound of a set-valued law (0 for the smooth laws, which have none)
  double static_bound_per_normal_force = 0.0;
  std::vector<double> static_bound_per_value;  // (values x 1)
};

// The partials of `law` at normal force N, slip velocity v and platform mode `mode` (a set-valued
// law's force is its kinetic force while slipping and no force while stuck, where the holding
// force is a constraint), in the law's units (F in newtons for a physical rig). Written into
// `out`, whose vectors keep their storage from call to call; false for a law that does not give
// them (the caller then differences its model instead).
bool frictionPartials(const FrictionLaw& law, double normal_force, double v, PlatformMode mode,
                      FrictionPartials& out);

}  // namespace metrosync
