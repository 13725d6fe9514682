// Shared by the validation tests: the shipped scenarios loaded from the source tree, and the
// engines that sim/analysis/validation/validation.h takes as functions (the Simbody full model, the
// Coulomb harness).
#pragma once

#include <string>
#include <vector>

#include "contact/simbody/driven_coulomb.h"
#include "sim/analysis/validation/validation.h"
#include "sim/engines/simbody/simbody_engine.h"
#include "yaml/rig_loader.h"

namespace metrosync::testval {

inline std::string rigsDir() {
  return std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs";
}

inline Scenario loadScenario(const std::string& name) {
  for (const auto& spec : shippedScenarios())
    if (spec.name == name) return {spec, computeScaled(loadRigFile(rigsDir() + "/" + spec.file))};
  throw std::invalid_argument("no shipped scenario named " + name);
}

inline std::vector<Scenario> loadScenarios() {
  std::vector<Scenario> all;
  for (const auto& spec : shippedScenarios()) all.push_back(loadScenario(spec.name));
  return all;
}

inline ValidationEngines engines() {
  ValidationEngines e;
  e.full_model = [](const Rig& rig, RunSink& sink) { return runSimbody(networkOfOne(rig), sink); };
  e.coulomb_probe = [](double s) { return measureDrivenCoulomb(s); };
  e.load_rig = [](const std::string& file, const std::vector<std::string>& sets) {
    return loadRigFile(rigsDir() + "/" + file, sets);
  };
  return e;
}

}  // namespace metrosync::testval
