// Pieces the laws' files share (contact/coulomb.cpp, static_coulomb.cpp, stribeck.cpp): a slip
// force of constant size values[kinetic] * N against the slip (Coulomb's) with its gradient, and
// the gradient of a bound values[index] * N.
#pragma once

#include "contact/platform_friction.h"

namespace metrosync {

inline double constantSlipForce(const LawConstants& k, int kinetic, PlatformMode mode) {
  return -(k.values[kinetic] * k.normal_force) * static_cast<int>(mode);
}

inline LawGradient constantSlipGradient(const LawConstants& k, int kinetic, PlatformMode mode) {
  LawGradient g;
  g.values[kinetic] = -k.normal_force * static_cast<int>(mode);
  g.normal_force = -k.values[kinetic] * static_cast<int>(mode);
  return g;
}

inline LawGradient boundGradient(const LawConstants& k, int index) {
  LawGradient g;
  g.values[index] = k.normal_force;
  g.normal_force = k.values[index];
  return g;
}

}  // namespace metrosync
