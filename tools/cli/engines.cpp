#include "tools/cli/engines.h"

#include "models/network_text.h"
#include "sim/engines/plugin_loader.h"
#include "tools/cli/exit_codes.h"
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

const Engine& chooseEngine(const std::string& requested, const std::string& model,
                           const Network& net, const std::string& rig_name,
                           const std::string& verb) {
  if (net.isSingleRig()) return chooseEngine(requested, model, net.platforms[0].rig, rig_name);
  const std::string what = "a " + networkOfPlatforms(net.platforms.size());
  const std::string full_only = " " + verb + " the full model only (--engine direct or simbody)";
  if (model == "slow")
    throw UsageError("--model slow: the slow flow is single-platform; " + what + full_only);
  const Engine& e = chooseEngine(requested, requested.empty() ? "full" : model,
                                 net.platforms.at(0).rig, rig_name);
  if (!e.runsNetworks()) throw UsageError("--engine " + e.name() + ": " + what + full_only);
  return e;
}

LoadOptions engineLoadOptions(double max_output_bytes) {
  LoadOptions lo;
  lo.max_output_bytes = max_output_bytes;
  for (const Engine* e : engines())
    for (const std::string& n : e->integrators()) lo.integrators.push_back(n);
  lo.integrator_help = "one of: " + integratorHelp();
  return lo;
}

void requireSlowFlow(const Rig& rig, const std::string& rig_name) {
  const SlowResponse r = rig.platform.friction.slowResponse();
  if (!r.available()) throw RigError(rig_name + ": the slow flow: " + r.why());
  if (const std::string key = rig.fullModelOnlyKey(); !key.empty())
    throw RigError(rig_name + ": the slow flow: " + key +
                   ": the air's drag has no averaged form in the slow flow; run the full model "
                   "(--model full)");
}

void requireDerivatives(const Rig& rig, const std::string& rig_name, const std::string& command) {
  if (const std::string key = rig.fullModelOnlyKey(); !key.empty())
    throw RigError(rig_name + ": " + key + ": " + command +
                   " has no air drag yet (its derivatives do not have it); `run`, `compare`, "
                   "`sweep`, `basin` and `animate` take it");
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
