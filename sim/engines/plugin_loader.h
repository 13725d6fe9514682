// Plugins (docs/bench/process.md): the parts of metrosync that bring a heavy shared library in --
// Simbody and LAPACK (the simbody engine), Ceres (fit, measure), Cairo (animate) -- are MODULE
// libraries that the `metrosync` executable dlopen()s the first time one of them runs, so that
// the direct engine and the slow flow start without mapping and relocating ~40 libraries. Each
// plugin exports one extern "C" entry point and takes everything else from the executable (which
// exports its symbols), so there is one copy of every piece of metrosync state.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace metrosync {

// A plugin that cannot be found or loaded, or is of another build: an installation problem,
// reported before anything is written (the commands' exit code 2).
struct PluginError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The folders searched for a plugin, in order: $METROSYNC_PLUGIN_DIR alone when it is set and not
// empty; else the executable's own folder (the build tree), then the install tree's
// <prefix>/<libdir>/metrosync (found from /proc/self/exe).
std::vector<std::string> pluginDirectories();

// The address of `symbol` in the plugin file `file` (e.g. "metrosync-simbody.so"), loaded once
// with RTLD_NOW (a symbol the plugin needs and the executable lacks fails here, not mid-run) and
// never unloaded. Throws PluginError naming the file, the folders searched and the loader's
// message.
void* loadPluginSymbol(const std::string& file, const char* symbol);

}  // namespace metrosync
