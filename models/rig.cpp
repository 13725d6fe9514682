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

std::string Rig::fullModelOnlyKey() const {
  for (std::size_t i = 0; i < metronomes.size(); ++i)
    if (!metronomes[i].locked && metronomes[i].air_drag_Nms2 != 0.0)
      return "metronomes." + std::to_string(i) + ".pendulum.air_drag";
  return "";
}

}  // namespace metrosync
