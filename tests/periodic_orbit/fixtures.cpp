#include "tests/periodic_orbit/fixtures.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/analysis/periodic_orbit/engine_trace.h"
#include "sim/engines/direct/direct_engine.h"
#include "sim/record/run_report.h"
#include "yaml/rig_loader.h"

namespace metrosync::orbit::testing {

Rig singleFixed(double A0, double tau) {
  const std::string yaml =
      "units: scaled\nepsilon: 0.073\nplatform: {friction: {law: fixed}}\n"
      "metronomes:\n  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: " +
      std::to_string(A0) + ", phi: 0.3}}\nsimulation: {tau: " + std::to_string(tau) + "}\n";
  return loadRigText(yaml, "single-fixed");
}

Rig shipped(const std::string& path, const std::vector<std::string>& sets) {
  return loadRigFile(std::string(METROSYNC_SOURCE_DIR) + "/" + path, sets);
}

Vec finalState(const Rig& rig, const ScaledModel& model, double accuracy) {
  Rig r = rig;
  r.sim.accuracy = accuracy;
  r.sim.sample_s = r.sim.t_end_s;
  FinalStateSink none;
  const RunReport rep = runDirectModel(r, none);
  EXPECT_TRUE(rep.complete) << rep.failure;
  return model.stateFromRow(rep.final_trajectory_row);
}

Orbit settledOrbit(const ReturnMap& map) {
  const Vec z = finalState(map.rig(), map.model(), map.settings().accuracy);
  const Pass first = map.firstCrossing(z, 3 * 2 * M_PI);
  std::string why;
  const auto orbit = shoot(map, first.u1, 2 * M_PI, {}, &why);
  EXPECT_TRUE(orbit.has_value()) << why;
  return orbit ? *orbit : Orbit{};
}

}  // namespace metrosync::orbit::testing
