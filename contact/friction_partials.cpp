#include "contact/friction_partials.h"

#include "contact/law_registry.h"

namespace metrosync {

bool frictionPartials(const FrictionLaw& law, double normal_force, double v, PlatformMode mode,
                      FrictionPartials& out) {
  const std::vector<double>& x = law.values();
  out.force_per_value.assign(x.size(), 0.0);
  out.static_bound_per_value.assign(x.size(), 0.0);
  out.force_per_velocity = out.force_per_normal_force = out.static_bound_per_normal_force = 0.0;
  const double slip = static_cast<int>(mode);  // -1, 0 (stuck: no force), +1
  if (law.is(coulombLaw()) || law.is(staticCoulombLaw())) {
    // slipping F = -mu N sign(v); the static bound mu_static N (mu_static = mu for Coulomb's)
    const int static_index = law.is(coulombLaw()) ? 0 : 1;
    out.force_per_value[0] = -normal_force * slip;
    out.force_per_normal_force = -x[0] * slip;
    out.static_bound_per_value[static_index] = normal_force;
    out.static_bound_per_normal_force = x[static_index];
    return true;
  }
  if (law.is(viscousLaw())) {  // F = -c v
    out.force_per_velocity = -x[0];
    out.force_per_value[0] = -v;
    return true;
  }
  // no friction, or a platform that does not move: no force at all
  return law.is(noFrictionLaw()) || law.is(fixedPlatformLaw());
}

}  // namespace metrosync
