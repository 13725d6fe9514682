#include "sim/engines/simbody/plugin.h"

#include "sim/engines/simbody/simbody_engine.h"

extern "C" const metrosync::SimbodyPlugin* metrosync_simbody_plugin() {
  static const metrosync::SimbodyPlugin table = [] {
    metrosync::SimbodyPlugin p;
    p.run = &metrosync::runSimbody;
    p.coulomb_probe = [](double B) { return metrosync::measureDrivenCoulomb(B); };
    return p;
  }();
  return &table;
}
