#include "tools/cli/network_sweep.h"

namespace metrosync::cli {

Rig networkSweepRig(const Network& net) {
  Rig rig = net.platforms.at(0).rig;
  rig.name = net.name;
  rig.metronomes.clear();
  for (const NetworkPlatform& p : net.platforms)
    rig.metronomes.insert(rig.metronomes.end(), p.rig.metronomes.begin(), p.rig.metronomes.end());
  return rig;
}

}  // namespace metrosync::cli
