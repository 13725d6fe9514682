// Item 3 of issue 17: a run's output is estimated before it starts and refused above the limit;
// t_end must be finite and the sample interval above the time resolution of t_end. The estimate
// is checked against what a real run writes.
#include <cmath>

#include "models/scaling.h"
#include "tests/hostile/hostile_support.h"

namespace metrosync::hostile {
namespace {

namespace fs = std::filesystem;

LoadOptions withLimit(double max_output_bytes) {
  LoadOptions o;
  o.max_output_bytes = max_output_bytes;
  return o;
}

std::size_t linesOf(const std::string& path) {
  const std::string text = testing_support::slurp(path);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// The estimate is an upper bound on the bytes a run writes, tight in rows: a 20 s run of the
// experiment rig at a given sample and at the engines' default.
TEST(HostileOutput, EstimateBoundsWhatARunWrites) {
  for (const std::string sample : {"0.01", ""}) {
    const std::string out = testing_support::scratchDir("hostile", "estimate");
    std::vector<std::string> sets = {"simulation.duration=20"};
    if (!sample.empty()) sets.push_back("simulation.sample=" + sample);
    std::string args = "run --quiet";
    for (const auto& s : sets) args += " --set " + s;
    const CommandResult r = runMetrosync(args + " --out " + shellQuote(out));
    ASSERT_EQ(r.code, 0) << r.err;
    const OutputEstimate e = estimateOutput(defaultRig(sets));
    // rows: the header line aside, within one row of the estimate
    const double traj_rows = static_cast<double>(linesOf(out + "/trajectory.csv")) - 1.0;
    const double env_rows = static_cast<double>(linesOf(out + "/envelope.csv")) - 1.0;
    EXPECT_NEAR(traj_rows, e.trajectory_rows, 1.0) << "sample " << sample;
    EXPECT_NEAR(env_rows, e.envelope_rows, 1.0) << "sample " << sample;
    const double written = static_cast<double>(fs::file_size(out + "/trajectory.csv") +
                                               fs::file_size(out + "/envelope.csv"));
    EXPECT_LE(written, e.bytes);
    EXPECT_GE(written, 0.5 * e.bytes) << "an estimate this loose would refuse reasonable runs";
    fs::remove_all(out);
  }
}

TEST(HostileOutput, RefusedAboveTheLimitWithTheEstimateAndTheWayOut) {
  const std::string rig = shippedRig("experiment.yaml");
  const std::vector<std::string> sets = {"simulation.duration=1e6", "simulation.sample=1e-3"};
  const OutputEstimate e = estimateOutput(loadRigText(rig, "r", sets));
  ASSERT_GT(e.bytes, kDefaultMaxOutputBytes);
  // no limit unless the caller gives one (a sweep point writes no trajectory)
  EXPECT_EQ(loadError(rig, sets), "");
  const std::string msg = loadError(rig, sets, withLimit(kDefaultMaxOutputBytes));
  EXPECT_EQ(msg.rfind("rig.yaml: --set simulation.sample=1e-3: simulation.sample = 1e-3: the run "
                      "would write about 1e+09 trajectory rows",
                      0),
            0u)
      << msg;
  EXPECT_NE(msg.find("--max-output BYTES"), std::string::npos) << msg;
  // the limit is the caller's: just above the estimate it loads, just below it does not
  EXPECT_EQ(loadError(rig, sets, withLimit(e.bytes * (1 + 1e-9))), "");
  EXPECT_NE(loadError(rig, sets, withLimit(e.bytes * (1 - 1e-9))), "");
  // without simulation.sample the run's length is blamed
  const std::string long_run =
      loadError(rig, {"simulation.duration=1e7"}, withLimit(kDefaultMaxOutputBytes));
  EXPECT_NE(long_run.find("simulation.duration = 1e7: the run would write"), std::string::npos)
      << long_run;
}

TEST(HostileOutput, CommandLineLiftsTheLimit) {
  const std::string out = testing_support::scratchDir("hostile", "maxout");
  const std::string sets = " --set simulation.duration=20 --set simulation.sample=0.001";
  CommandResult r = runLimited("run --quiet --max-output 1e5" + sets, out);
  expectRefusedCleanly(r, out, "--max-output 1e5");
  EXPECT_NE(r.err.find("above the output limit of 100000 bytes"), std::string::npos) << r.err;
  r = runMetrosync("run --quiet --max-output 1e8" + sets + " --out " + shellQuote(out));
  EXPECT_EQ(r.code, 0) << r.err;
  fs::remove_all(out);
}

TEST(HostileOutput, EndMustBeFiniteAndSampleAboveItsResolution) {
  const std::string scaled = shippedRig("experiment-scaled.yaml");
  const ScaledParams p = computeScaled(loadRigText(scaled, "s"));
  // tau is finite, tau / epsilon is not
  const double tau = 1e308;
  ASSERT_TRUE(std::isinf(tau / p.epsilon));
  const std::string inf = loadError(scaled, {"simulation.tau=1e308"});
  EXPECT_NE(inf.find("simulation.tau = 1e308: the run would end at t = inf"), std::string::npos)
      << inf;

  // the experiment runs 200 s: the resolution is 200 * kSampleResolution
  const std::string rig = shippedRig("experiment.yaml");
  const double resolution = 200 * kSampleResolution;
  char above[32], below[32];
  std::snprintf(above, sizeof above, "%.17g", resolution * 1.01);
  std::snprintf(below, sizeof below, "%.17g", resolution * 0.99);
  const std::string ok =
      loadError(rig, {std::string("simulation.sample=") + above}, withLimit(HUGE_VAL));
  EXPECT_EQ(ok, "");
  const std::string bad = loadError(rig, {std::string("simulation.sample=") + below});
  EXPECT_NE(bad.find("below the time resolution of the run"), std::string::npos) << bad;
  EXPECT_NE(loadError(rig, {"simulation.sample=1e-300"}).find("below the time resolution"),
            std::string::npos);
}

}  // namespace
}  // namespace metrosync::hostile
