// simbodyIntegratorNames() apart from the engine: the registry lists and checks these names
// without loading Simbody (this file is compiled into sim/engines, not into the plugin).
#include "sim/engines/simbody/simbody_engine.h"

namespace metrosync {

const std::vector<std::string>& simbodyIntegratorNames() {
  static const std::vector<std::string> names = {
      "rk-merson", "rk-feldberg", "rk3", "rk2", "cpodes", "verlet", "semi-explicit-euler2"};
  return names;
}

}  // namespace metrosync
