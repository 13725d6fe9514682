#include "sim/engines/simbody_plugin.h"

#include "sim/engines/plugin_loader.h"

// Weak: defined when sim/engines/simbody/plugin.cpp is linked into this binary (the tests, the
// Python module), null in the `metrosync` executable, which loads it from the plugin instead.
extern "C" const metrosync::SimbodyPlugin* metrosync_simbody_plugin() __attribute__((weak));

namespace metrosync {

namespace {

using Entry = const SimbodyPlugin* (*)();

const SimbodyPlugin* loadTable() {
  Entry entry = &metrosync_simbody_plugin;
  if (!entry)
    entry =
        reinterpret_cast<Entry>(loadPluginSymbol(kSimbodyPluginFile, "metrosync_simbody_plugin"));
  const SimbodyPlugin* table = entry();
  if (!table || table->abi != kSimbodyPluginAbi)
    throw PluginError(std::string("the plugin ") + kSimbodyPluginFile +
                      " is of another metrosync build (interface " +
                      std::to_string(table ? table->abi : 0) + ", expected " +
                      std::to_string(kSimbodyPluginAbi) + "); reinstall metrosync");
  return table;
}

}  // namespace

const SimbodyPlugin& simbodyPlugin() {
  static const SimbodyPlugin* table = loadTable();  // a throw leaves it for the next call
  return *table;
}

}  // namespace metrosync
