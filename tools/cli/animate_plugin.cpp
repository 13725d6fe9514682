#include "tools/cli/animate_plugin.h"

#include <string>

#include "sim/engines/plugin_loader.h"

// Weak: defined when animate_render.cpp is linked into this binary (test_animate), null in the
// `metrosync` executable, which loads it from metrosync-animate.so instead.
extern "C" const metrosync::cli::AnimatePlugin* metrosync_animate_plugin() __attribute__((weak));

namespace metrosync::cli {

namespace {

using Entry = const AnimatePlugin* (*)();

const AnimatePlugin* loadTable() {
  Entry entry = &metrosync_animate_plugin;
  if (!entry)
    entry =
        reinterpret_cast<Entry>(loadPluginSymbol(kAnimatePluginFile, "metrosync_animate_plugin"));
  const AnimatePlugin* table = entry();
  if (!table || table->abi != kAnimatePluginAbi)
    throw PluginError(std::string("the plugin ") + kAnimatePluginFile +
                      " is of another metrosync build; reinstall metrosync");
  return table;
}

}  // namespace

const AnimatePlugin& animatePlugin() {
  static const AnimatePlugin* table = loadTable();  // a throw leaves it for the next call
  return *table;
}

}  // namespace metrosync::cli
