// The Simbody engine's functions (sim/engines/simbody/plugin.h) as this process has them: linked
// in (the tests, the Python module, metrosync-mpi) or, in the `metrosync` executable, from the
// plugin metrosync-simbody.so, loaded on first use (sim/engines/plugin_loader.h).
#pragma once

#include "sim/engines/simbody/plugin.h"

namespace metrosync {

// The plugin's file name, in the folders of pluginDirectories().
inline constexpr const char* kSimbodyPluginFile = "metrosync-simbody.so";

// Loads the plugin on the first call (thread-safe); throws PluginError when it cannot.
const SimbodyPlugin& simbodyPlugin();

}  // namespace metrosync
