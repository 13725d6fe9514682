// `metrosync run` as a method of the bench (tools/bench/run_method.h): the built binary run on a
// bench scene gives the same steps, events and final state as the direct engine in the bench's
// own process (its final state read back from trajectory.csv's last row), its summary's timings,
// and a failure said with its reason; precision with the method writes `run`'s points against
// its engine (runpoints.csv). No timing is checked.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "tests/bench/bench_rig.h"
#include "tests/common/run_metrosync.h"
#include "tools/bench/bench_run.h"
#include "tools/bench/run_method.h"
#include "tools/bench/wp_csv.h"

using metrosync::testing_support::benchRig;

namespace mb = metrosync::bench;
namespace ts = metrosync::testing_support;
namespace fs = std::filesystem;

namespace {

// trajectory.csv writes 12 significant digits: the state read back is that close
constexpr double kTrajectoryDigits = 1e-11;

}  // namespace

TEST(RunMethod, TheLastCsvRowIsReadFromTheEnd) {
  const fs::path dir = ts::scratchDir("bench", "lastrow", true);
  const fs::path p = dir / "t.csv";
  {
    std::ofstream f(p);
    f << "t,x,xdot\n";
    for (int k = 0; k < 20000; ++k) f << k << ",0.5,-1.25e-3\n";  // longer than one read
  }
  EXPECT_EQ(mb::lastCsvRow(p.string()), (std::vector<double>{19999, 0.5, -1.25e-3}));
  std::ofstream(p) << "t,x\n1,2";  // no newline at the end
  EXPECT_EQ(mb::lastCsvRow(p.string()), (std::vector<double>{1, 2}));
  std::ofstream(p) << "t,x\n";  // the header alone
  EXPECT_TRUE(mb::lastCsvRow(p.string()).empty());
  std::ofstream(p) << "t,x\n1,two\n";
  EXPECT_TRUE(mb::lastCsvRow(p.string()).empty());
  EXPECT_TRUE(mb::lastCsvRow((dir / "absent.csv").string()).empty());
  fs::remove_all(dir);
}

TEST(RunMethod, RunGivesTheEnginesStepsEventsAndFinalState) {
  mb::setMetrosyncPath(METROSYNC_BINARY);
  for (const char* name : {"peer-n2", "experiment-short"}) {  // scaled and physical units
    const mb::Scene scene = mb::loadScene(benchRig(name));
    const mb::Method run = mb::parseMethod("run:verner76:1e-8");
    const mb::RunCall call = mb::runMetrosyncCommand(scene, run, 2, 300);
    ASSERT_TRUE(call.result.complete) << call.result.failure;
    EXPECT_EQ(call.runs, 2);
    const mb::RunResult engine =
        mb::runOnce(scene, mb::parseMethod("direct:verner76:1e-8"), 300, mb::Sampling::FinalState);
    EXPECT_EQ(call.result.counts.steps, engine.counts.steps) << name;
    EXPECT_EQ(call.result.counts.rhs_evals, engine.counts.rhs_evals) << name;
    EXPECT_EQ(call.result.counts.events, engine.counts.events) << name;
    ASSERT_EQ(call.result.final_state.size(), engine.final_state.size());
    for (size_t k = 0; k < engine.final_state.size(); ++k)
      EXPECT_NEAR(call.result.final_state[k], engine.final_state[k],
                  kTrajectoryDigits * std::max(1.0, std::abs(engine.final_state[k])))
          << name << " " << k;
    // summary.json's split: the engine's time is part of the run's
    EXPECT_GT(call.result.engine_s, 0.0);
    EXPECT_GE(call.result.wall_over_engine, 1.0);
    EXPECT_TRUE(std::isnan(call.result.cpu_s));
    EXPECT_NE(call.command.find("--set simulation.accuracy=1e-08"), std::string::npos)
        << call.command;
  }
}

TEST(RunMethod, AFailureIsSaidWithItsReason) {
  mb::setMetrosyncPath(METROSYNC_BINARY);
  mb::Scene scene = mb::loadScene(benchRig("peer-n2"));
  scene.path = "/nonexistent/rig.yaml";
  const mb::RunCall call = mb::runMetrosyncCommand(scene, mb::parseMethod("run:verner76"), 1, 60);
  EXPECT_FALSE(call.result.complete);
  EXPECT_NE(call.result.failure.find("metrosync run failed (exit 2: "), std::string::npos)
      << call.result.failure;
  scene.path.clear();
  EXPECT_NE(mb::runMetrosyncCommand(scene, mb::parseMethod("run:verner76"), 1, 60)
                .result.failure.find("needs a rig file"),
            std::string::npos);
}

TEST(RunMethod, PrecisionWritesRunsPointsAgainstItsEngine) {
  const fs::path dir = ts::scratchDir("bench", "runmethod", true);
  const auto r = ts::runCommand(
      ts::shellQuote(METROSYNC_BENCH_BINARY) + " precision --scene " +
      ts::shellQuote(benchRig("peer-n2")) + " --metrosync " + ts::shellQuote(METROSYNC_BINARY) +
      " --methods direct:verner76,run:verner76 --accuracies 1e-6,1e-8 --repeat 1 --max-load 0 "
      "--reference direct:verner76:1e-11 --cross-check direct:verner76:1e-10 --quiet --out " +
      ts::shellQuote(dir.string()));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = ts::csvRows((dir / "runpoints.csv").string());
  ASSERT_EQ(rows.size(), 3u);  // the header, two points
  EXPECT_EQ(rows[1][1], "run:verner76:1e-06");
  for (size_t k = 1; k < rows.size(); ++k) {
    EXPECT_GE(std::stod(rows[k][4]), 1.0);  // wall_seconds / engine_seconds
    EXPECT_GT(std::stod(rows[k][5]), 0.0);  // the engine alone at the same setting
  }
  // the run's final-state error is the engine's: the same steps to the same state
  const auto scenes =
      mb::parseWorkPrecisionCsv(ts::slurp((dir / "wp-peer-n2.csv").string()), "wp-peer-n2.csv");
  ASSERT_EQ(scenes.size(), 1u);
  ASSERT_EQ(scenes[0].run.size(), 2u);
  ASSERT_EQ(scenes[0].ours.size(), 2u);
  for (size_t k = 0; k < 2; ++k)
    EXPECT_NEAR(scenes[0].run[k].err_final, scenes[0].ours[k].err_final, 10 * kTrajectoryDigits)
        << scenes[0].run[k].method;
  EXPECT_TRUE(fs::exists(dir / "runpoints.md"));
  fs::remove_all(dir);
}
