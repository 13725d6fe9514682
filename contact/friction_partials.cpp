#include "contact/friction_partials.h"

namespace metrosync {

// Every law gives its own derivatives (contact/platform_friction.h: forceSlope, forceGradient,
// staticBoundGradient), so every registered law has partials.
bool frictionPartials(const FrictionLaw& law, double normal_force, double v, PlatformMode mode,
                      FrictionPartials& out) {
  const std::size_t n = law.values().size();
  const PlatformFriction f = law.platform(normal_force);
  const LawGradient force = f.forceGradient(v, mode), bound = f.staticBoundGradient();
  out.force_per_velocity = f.forceSlope(v, mode);
  out.force_per_normal_force = force.normal_force;
  out.static_bound_per_normal_force = bound.normal_force;
  out.force_per_value.assign(force.values.begin(), force.values.begin() + n);
  out.static_bound_per_value.assign(bound.values.begin(), bound.values.begin() + n);
  return true;
}

}  // namespace metrosync
