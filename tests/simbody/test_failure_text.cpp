// A failed run's message has one form on both engines (sim/record/failure_text.h): "simulation
// failed at t = T: why", T in the run's own time unit -- a scaled rig's scaled time, with its slow
// time; a network's seconds. Before, a network's message was "at t = T s: why" (the direct engine
// with six fixed decimals, Simbody with %g), and the direct engine gave a scaled rig's T in
// seconds where Simbody gave it in scaled time.
#include <gtest/gtest.h>

#include <regex>
#include <stdexcept>
#include <string>

#include "rigs.h"
#include "sim/engines/engine.h"
#include "yaml/network_loader.h"

namespace metrosync {
namespace {

const std::string kRigs = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/";

// Fails the run from its third row (or state): the engine reports the sink's error as its failure.
struct FailingSink : RunSink {
  void trajectoryRow(const std::vector<double>& row) override {
    if (++rows == 3) throw std::runtime_error("the sink failed");
    t = row[0];
  }
  bool wantsStates() const override { return states; }
  void stateSample(double ts, const std::vector<double>&,
                   const std::vector<PlatformMode>&) override {
    if (++rows == 3) throw std::runtime_error("the sink failed");
    t = ts;
  }
  int rows = 0;
  double t = 0.0;  // the last row's time, in the rows' unit
  bool states = false;
};

// T of "simulation failed at t = T<unit> (...)" or nothing when the form differs.
std::optional<double> failedAt(const std::string& text, const std::string& unit_and_rest) {
  const std::regex form("^simulation failed at t = ([-+0-9.e]+)" + unit_and_rest +
                        ": the sink failed$");
  std::smatch m;
  if (!std::regex_match(text, m, form)) return std::nullopt;
  return std::stod(m[1]);
}

TEST(FailureText, AScaledRigsFailureIsInScaledTimeOnBothEngines) {
  ScaledRigInput in = testrigs::scaledPair(0.1, FrictionLaw::coulomb(0.2), 10.0, 1.0);
  const Rig rig = rigFromScaled(in);
  ASSERT_EQ(rig.units, Units::Scaled);
  for (const char* engine : {"direct", "simbody"}) {
    FailingSink sink;
    const RunReport r = findEngine(engine)->run(rig, sink);
    ASSERT_FALSE(r.complete) << engine;
    const std::optional<double> t = failedAt(r.failure, R"( \(tau = [-+0-9.e]+\))");
    ASSERT_TRUE(t) << engine << ": " << r.failure;
    // at the failing row, in its unit (the rows' scaled time), within a step of it
    EXPECT_NEAR(*t, sink.t, 2.0) << engine << ": " << r.failure;
  }
}

TEST(FailureText, ANetworksFailureIsInSecondsOnBothEngines) {
  const Network net = loadNetworkFile(kRigs + "two-boards-rollers.yaml");
  for (const char* engine : {"direct", "simbody"}) {
    FailingSink sink;
    sink.states = true;
    const RunReport r = findEngine(engine)->run(net, sink);
    ASSERT_FALSE(r.complete) << engine;
    const std::optional<double> t = failedAt(r.failure, " s");
    ASSERT_TRUE(t) << engine << ": " << r.failure;
    EXPECT_NEAR(*t, sink.t, 0.1) << engine << ": " << r.failure;
  }
}

}  // namespace
}  // namespace metrosync
