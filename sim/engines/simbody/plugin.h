// The Simbody engine's plugin interface (docs/bench/process.md): everything of metrosync that
// needs Simbody (and through it LAPACK) -- the full model of a network as a multibody system (a
// single rig is the network of one), the Coulomb element's harness -- behind one table of
// functions, so that the `metrosync` executable loads Simbody only when one of them runs. The table
// is exported as `metrosync_simbody_plugin` by the plugin metrosync-simbody.so (dlopen'ed by
// sim/engines/simbody_plugin.h) and linked in directly by the tests and the Python module.
// No Simbody type appears here.
#pragma once

#include "contact/simbody/driven_coulomb.h"
#include "models/network.h"
#include "models/rig.h"
#include "sim/record/run_report.h"

namespace metrosync {

// Raised whenever the table changes: a plugin of another build is refused, not called.
constexpr int kSimbodyPluginAbi = 3;  // 3: RunSink::poll

struct SimbodyPlugin {
  int abi = kSimbodyPluginAbi;
  // runSimbody: a network, a single rig being networkOfOne(rig)
  RunReport (*run)(const Network&, RunSink&) = nullptr;
  DrivenCoulombMeasurement (*coulomb_probe)(double B) = nullptr;  // measureDrivenCoulomb(B)
};

}  // namespace metrosync

// The plugin's one entry point (its symbol name is kSimbodyPluginSymbol).
extern "C" const metrosync::SimbodyPlugin* metrosync_simbody_plugin();
