#include "sim/analysis/fit/ceres_plugin.h"

#include <string>

#include "sim/engines/plugin_loader.h"

// Weak: defined when ceres_solve.cpp is linked into this binary (the tests, the Python module),
// null in the `metrosync` executable, which loads it from metrosync-ceres.so instead.
extern "C" const metrosync::CeresPlugin* metrosync_ceres_plugin() __attribute__((weak));

namespace metrosync {

namespace {

using Entry = const CeresPlugin* (*)();

const CeresPlugin* loadTable() {
  Entry entry = &metrosync_ceres_plugin;
  if (!entry)
    entry = reinterpret_cast<Entry>(loadPluginSymbol(kCeresPluginFile, "metrosync_ceres_plugin"));
  const CeresPlugin* table = entry();
  if (!table || table->abi != kCeresPluginAbi)
    throw PluginError(std::string("the plugin ") + kCeresPluginFile +
                      " is of another metrosync build; reinstall metrosync");
  return table;
}

}  // namespace

const CeresPlugin& ceresPlugin() {
  static const CeresPlugin* table = loadTable();  // a throw leaves it for the next call
  return *table;
}

}  // namespace metrosync
