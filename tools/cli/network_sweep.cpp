#include "tools/cli/network_sweep.h"

#include <cmath>

#include "tools/cli/engines.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

Rig networkSweepRig(const Network& net) {
  Rig rig = net.platforms.at(0).rig;
  rig.name = net.name;
  rig.metronomes.clear();
  for (const NetworkPlatform& p : net.platforms)
    rig.metronomes.insert(rig.metronomes.end(), p.rig.metronomes.begin(), p.rig.metronomes.end());
  return rig;
}

Rig loadSweepRig(const std::string& text, const std::string& name,
                 const std::vector<std::string>& sets, std::optional<Network>* net) {
  if (!isNetworkText(text)) return loadRigText(text, name, sets);
  Network loaded = loadNetworkText(text, name, sets, engineLoadOptions(HUGE_VAL));
  if (loaded.isSingleRig()) return loaded.toSingleRig();
  Rig rig = networkSweepRig(loaded);
  if (net) *net = std::move(loaded);
  return rig;
}

}  // namespace metrosync::cli
