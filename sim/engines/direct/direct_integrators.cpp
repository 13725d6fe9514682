#include "sim/engines/direct/direct_integrators.h"

namespace metrosync {

const std::vector<std::string>& directIntegratorNames() {
  static const std::vector<std::string> names = {"verner76", "dopri5", "verner65"};
  return names;
}

std::string defaultDirectIntegrator(const Rig& rig) {
  return rig.numSwinging() > 8 ? "dopri5" : "verner76";
}

}  // namespace metrosync
