#include "tools/cli/engines.h"

#include <algorithm>

#include "sim/engines/direct/direct_engine.h"
#include "sim/engines/simbody/simbody_engine.h"
#include "tools/cli/commands.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

namespace {

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

std::string list(const std::vector<std::string>& v) {
  std::string s;
  for (size_t k = 0; k < v.size(); ++k) s += (k ? ", " : "") + v[k] + (k == 0 ? " (default)" : "");
  return s;
}

}  // namespace

std::string chooseEngine(const std::string& requested, const Rig& rig,
                         const std::string& rig_name) {
  const auto& engines = availableEngines();
  if (!requested.empty() && !contains(engines, requested))
    throw UsageError("--engine " + requested +
                     ": not available in this build (available: " + list(engines) + ")");
  const std::string& integ = rig.sim.integrator;
  const bool simbody_name = contains(simbodyIntegratorNames(), integ);
  const bool direct_name = contains(directIntegratorNames(), integ);
  if (!integ.empty() && !simbody_name && !direct_name)
    throw RigError(rig_name + ": simulation.integrator = " + integ +
                   ": unknown integrator; one of: " + integratorHelp());
  const std::string engine = !requested.empty() ? requested : (simbody_name ? "simbody" : "direct");
  if (engine == "direct" && simbody_name)
    throw RigError(rig_name + ": simulation.integrator = " + integ +
                   ": a Simbody integrator, for --engine simbody only; the direct engine's are " +
                   integratorHelp());
  if (engine == "simbody" && direct_name)
    throw RigError(
        rig_name + ": simulation.integrator = " + integ +
        ": an integrator of the direct engine, for --engine direct only; Simbody's are " +
        list(simbodyIntegratorNames()));
  return engine;
}

RunReport runFullModelOn(const std::string& engine, const Rig& rig, RunSink& sink) {
  if (engine == "direct") return runDirectModel(rig, sink);
  return runFullModel(rig, sink);
}

std::string integratorHelp() {
  std::string direct;
  for (const auto& n : directIntegratorNames()) direct += (direct.empty() ? "" : ", ") + n;
  return "direct engine: " + direct +
         " (default: verner76, or dopri5 for more than 8 swinging metronomes); simbody engine: " +
         list(simbodyIntegratorNames());
}

}  // namespace metrosync::cli
