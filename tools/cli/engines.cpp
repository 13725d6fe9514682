#include "tools/cli/engines.h"

#include "sim/engines/plugin_loader.h"
#include "tools/cli/commands.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

const Engine& chooseEngine(const std::string& requested, const std::string& model, const Rig& rig,
                           const std::string& rig_name) {
  try {
    const Engine& e = selectEngine(requested, model, rig.sim.integrator);
    if (e.model() == "slow") requireSlowFlow(rig, rig_name);
    return e;
  } catch (const EngineSelectionError& e) {
    if (e.about_integrator) throw RigError(rig_name + ": " + e.what());
    throw UsageError(e.what());
  } catch (const PluginError& e) {
    throw UsageError(e.what());  // exit 2, before anything is written
  }
}

void requireSlowFlow(const Rig& rig, const std::string& rig_name) {
  const SlowResponse r = rig.platform.friction.slowResponse();
  if (r.kind == SlowResponse::Kind::None) throw RigError(rig_name + ": the slow flow: " + r.why);
}

std::string fullEngineHelp() {
  return "engine of the full model: direct (minimal coordinates; the default) or simbody (the "
         "default when simulation.integrator names a Simbody integrator)";
}

std::string anyEngineHelp() {
  return "engine: direct, simbody (the full model) or slowflow (the slow flow); default: the "
         "model's own (direct, or simbody when simulation.integrator names a Simbody "
         "integrator; slowflow for --model slow)";
}

}  // namespace metrosync::cli
