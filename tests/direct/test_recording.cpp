// What the engines record never changes what they integrate, and the run's time is split into the
// engine's and the recording's part (RunReport::engine_seconds, summary.json engine_seconds).
// A sink that takes no trajectory and no envelope (the benchmark's, timing the integrator alone)
// gets the same steps, evaluations, events and final state, to the last bit, as one that takes
// every row: samples come from the interpolant and never stop or steer the integrator.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sim/engines/direct/direct_engine.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

// Counts what it receives and declares which rows it takes.
struct CountingSink : RunSink {
  CountingSink(bool rows, bool envelope) : rows_(rows), envelope_(envelope) {}
  bool wantsTrajectory() const override { return rows_; }
  bool wantsEnvelope() const override { return envelope_; }
  void trajectoryRow(const std::vector<double>&) override { ++rows; }
  void envelopeRow(const EnvelopeRow&) override { ++envelope; }
  long rows = 0, envelope = 0;

 private:
  bool rows_, envelope_;
};

Rig rigFrom(const std::string& yaml) {
  return loadRigText(yaml, "test.yaml");
}

// two detuned metronomes on a sliding board, and eight (the fixed-size paths N = 2 and N = 8)
const char* kPair = R"(units: scaled
epsilon: 0.073
platform: {friction: {law: coulomb, mu: 0.23}}
metronomes:
  - {nu: 0.65, J: 3.14, theta_c: 0.9, start: {A: 2.9, phi: 0.3}}
  - {nu: 0.65, J: 3.14, theta_c: 0.9, alpha: 0.1, start: {A: 2.5, phi: 0.0}}
simulation: {tau: 5}
)";

std::string eight() {
  std::string s =
      "units: scaled\nepsilon: 0.05\nplatform: {friction: {law: coulomb, mu: 0.6}}\n"
      "metronomes:\n";
  for (int i = 0; i < 8; ++i)
    s += "  - {nu: 0.65, J: 3.14, theta_c: 0.9, alpha: " + std::to_string(0.05 * i) +
         ", start: {A: 2.6, phi: " + std::to_string(0.8 * i) + "}}\n";
  return s + "simulation: {tau: 3}\n";
}

void expectSameIntegration(const Rig& rig) {
  CountingSink all(true, true), none(false, false), rows_only(true, false);
  const RunReport a = runDirectModel(rig, all);
  const RunReport b = runDirectModel(rig, none);
  const RunReport c = runDirectModel(rig, rows_only);
  ASSERT_TRUE(a.complete && b.complete && c.complete);
  EXPECT_GT(all.rows, 10);
  EXPECT_GT(all.envelope, 2);
  EXPECT_EQ(none.rows, 0);
  EXPECT_EQ(none.envelope, 0);
  EXPECT_EQ(rows_only.envelope, 0);
  EXPECT_EQ(rows_only.rows, all.rows);
  for (const RunReport* r : {&b, &c}) {
    EXPECT_EQ(r->counts.steps, a.counts.steps);
    EXPECT_EQ(r->counts.events, a.counts.events);
    EXPECT_EQ(r->counts.escapements, a.counts.escapements);
    EXPECT_EQ(r->final_trajectory_row, a.final_trajectory_row);  // bit for bit
  }
  // the interpolant's extra stages are evaluated only where a sample or an event needs them
  EXPECT_LE(b.counts.rhs_evals, a.counts.rhs_evals);
  for (const RunReport* r : {&a, &b, &c}) {
    EXPECT_GT(r->engine_seconds, 0.0);
    EXPECT_LE(r->engine_seconds, r->wall_seconds);
  }
}

TEST(Recording, NeverChangesWhatTheEngineIntegratesTwoMetronomes) {
  expectSameIntegration(rigFrom(kPair));
}

TEST(Recording, NeverChangesWhatTheEngineIntegratesEightMetronomes) {
  expectSameIntegration(rigFrom(eight()));
}

}  // namespace
}  // namespace metrosync
