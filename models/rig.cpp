#include "models/rig.h"

namespace metrosync {

const char* toString(Units u) {
  return u == Units::Physical ? "physical" : "scaled";
}

double Rig::totalMass() const {
  double m = platform.mass_kg;
  for (const auto& mt : metronomes) m += mt.box_mass_kg + mt.pendulum_mass_kg;
  return m;
}

int Rig::numSwinging() const {
  int n = 0;
  for (const auto& mt : metronomes) n += mt.locked ? 0 : 1;
  return n;
}

}  // namespace metrosync
