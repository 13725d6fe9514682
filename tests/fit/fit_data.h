// What the fit tests share: three rigs, data made by an engine with a camera's noise, and running
// `metrosync fit` in a scratch directory.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "sim/engines/engine.h"
#include "tests/common/run_metrosync.h"
#include "yaml/rig_loader.h"

namespace metrosync::fit_testing {

constexpr double kNoiseRad = 1e-3;  // the issue's camera noise
constexpr double kSampleS = 0.01;   // 100 Hz

// Two Wittner metronomes on the low-friction board (yaml/rigs/experiment.yaml), run for 6 s.
inline const char* kPairRig = R"(units: physical
name: pair
platform:
  mass: 0.1432
  friction: {law: coulomb, mu: 6.5e-4}
metronomes:
  - name: A
    box_mass: 0.0602
    pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}
    escapement: {angle: 0.244, steady_amplitude: 0.785}
    start: {angle: 0.785, rate: 0.0}
  - name: B
    box_mass: 0.0602
    pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}
    escapement: {angle: 0.244, steady_amplitude: 0.785}
    start: {angle: -0.785, rate: 0.25}
simulation:
  duration: 6
)";

// The experiment's pair with the paper's keys: damping (kg/s) and impulse (N m s), 15 s.
inline const char* kFiveKeyRig = R"(units: physical
name: five
platform:
  mass: 0.1432
  friction: {law: coulomb, mu: 6.5e-4}
metronomes:
  - name: A
    box_mass: 0.0602
    pendulum: {mass: 0.0226, length: 0.0225, damping: 0.0226}
    escapement: {angle: 0.244, impulse: 1.4844e-5}
    start: {angle: 0.785, rate: 0.0}
  - name: B
    box_mass: 0.0602
    pendulum: {mass: 0.0226, length: 0.0225, damping: 0.0226}
    escapement: {angle: 0.244, impulse: 1.4844e-5}
    start: {angle: -0.785, rate: 0.25}
simulation:
  duration: 15
)";

// One metronome on a still table (the platform fixed), started below theta_c: a free decay.
inline const char* kDecayRig = R"(units: physical
name: decay
platform:
  mass: 0.1432
  friction: {law: fixed}
metronomes:
  - name: A
    box_mass: 0.0602
    pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}
    escapement: {angle: 0.244, steady_amplitude: 0.785}
    start: {angle: 0.2, rate: 0.0}
simulation:
  duration: 10
)";

inline void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

inline nlohmann::json readJson(const std::string& path) {
  return nlohmann::json::parse(testing_support::slurp(path));
}

// The theta columns of `rig_yaml` (with `sets`) run by `engine` every 10 ms (every `stride` x
// 10 ms), plus N(0, kNoiseRad) noise; a fraction `lost` of the cells left empty (frames a tracker
// lost).
inline std::string noisyData(const std::string& rig_yaml, const std::vector<std::string>& sets,
                             unsigned seed, int stride = 1, double lost = 0.0,
                             const std::string& engine = "direct") {
  Rig rig = loadRigText(rig_yaml, "rig.yaml", sets);
  rig.sim.sample_s = kSampleS;
  MemorySink sink;
  const RunReport rep = selectEngine(engine, "full", "").run(rig, sink);
  EXPECT_TRUE(rep.complete) << rep.failure;
  std::mt19937 gen(seed);
  std::normal_distribution<double> noise(0.0, kNoiseRad);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const std::size_t n = rig.metronomes.size();
  std::ostringstream os;
  os.precision(12);
  os << "t";
  for (std::size_t i = 0; i < n; ++i) os << ",theta_" << i + 1;
  os << "\n";
  for (std::size_t k = 0; k < sink.trajectory.size(); k += stride) {
    const std::vector<double>& row = sink.trajectory[k];
    os << row[0];
    for (std::size_t i = 0; i < n; ++i) {
      os << ",";
      if (uniform(gen) >= lost) os << row[3 + 2 * i] + noise(gen);
    }
    os << "\n";
  }
  return os.str();
}

// fit RIG DATA --free ... in directory `dir` (rig.yaml and data.csv written there); fit.json.
inline nlohmann::json fitIn(const std::string& dir, const std::string& rig, const std::string& data,
                            const std::string& args) {
  writeText(dir + "/rig.yaml", rig);
  writeText(dir + "/data.csv", data);
  const auto r = testing_support::runMetrosync(
      "fit rig.yaml data.csv --out out --no-plot -q " + args, {dir, ""});
  EXPECT_EQ(r.code, 0) << r.err;
  return readJson(dir + "/out/fit.json");
}

}  // namespace metrosync::fit_testing
