#include "sim/engines/simbody/plugin.h"

#include "sim/engines/simbody/network_simbody_engine.h"
#include "sim/engines/simbody/simbody_engine.h"

extern "C" const metrosync::SimbodyPlugin* metrosync_simbody_plugin() {
  static const metrosync::SimbodyPlugin table = [] {
    metrosync::SimbodyPlugin p;
    p.run = &metrosync::runFullModel;
    p.run_network = &metrosync::runNetworkSimbody;
    p.coulomb_probe = [](double B) { return metrosync::measureDrivenCoulomb(B); };
    return p;
  }();
  return &table;
}
