// metrosync_bench's subcommands of issue 36 end to end, on tiny settings or stand-ins: `process`
// (the whole process of `metrosync run` tiled by its phases), `eventcost` (cost per step and per
// event against one RHS evaluation), `fitcost` (a stand-in fit bench, the real `run` of its
// record) and `continue` (a stand-in metrosync, finished and stopped). No timing is checked
// against a target: only that the parts add up and the files say what was measured.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "tests/bench/bench_rig.h"
#include "tests/common/run_metrosync.h"
#include "tools/bench/csv_table.h"

using metrosync::testing_support::benchRig;

namespace mb = metrosync::bench;
namespace ts = metrosync::testing_support;
namespace fs = std::filesystem;

namespace {

// `metrosync_bench ARGS --max-load 0 --quiet --out DIR`
ts::CommandResult bench(const std::string& args, const fs::path& dir) {
  return ts::runCommand(ts::shellQuote(METROSYNC_BENCH_BINARY) + " " + args +
                        " --max-load 0 --quiet --out " + ts::shellQuote(dir.string()));
}

mb::CsvTable table(const fs::path& p) {
  return mb::parseCsvTable(ts::slurp(p.string()), p.filename().string());
}

fs::path script(const fs::path& dir, const std::string& name, const std::string& body) {
  const fs::path p = dir / name;
  std::ofstream(p) << "#!/bin/sh\n" << body;
  ::chmod(p.c_str(), 0755);
  return p;
}

}  // namespace

TEST(ProcessCost, ThePhasesTileTheWholeProcess) {
  const fs::path dir = ts::scratchDir("bench", "process", true);
  const auto r = bench("process --metrosync " + ts::shellQuote(METROSYNC_BINARY) + " --scene " +
                           ts::shellQuote(benchRig("peer-n2")) + " --repeat 1",
                       dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const mb::CsvTable c = table(dir / "process.csv");
  ASSERT_EQ(c.rows.size(), 1u);
  // one counted run: each part's median is that run's, and the parts add up to the whole
  double parts = 0;
  for (const char* p :
       {"start-up", "args", "rig", "folder", "run", "files", "summary", "sync", "print", "exit"}) {
    const double ms = c.number(0, std::string(p) + "_ms");
    EXPECT_GE(ms, 0.0) << p;
    parts += ms;
  }
  EXPECT_NEAR(parts, c.number(0, "total_ms"), 0.01);
  EXPECT_GE(c.number(0, "run_ms"), c.number(0, "wall_seconds_ms"));  // the run holds wall_seconds
  // process.csv's numbers have 6 significant digits
  const double budget = 1.5 * c.number(0, "wall_seconds_ms") + 3;
  EXPECT_NEAR(c.number(0, "budget_ms"), budget, 1e-5 * budget);
  EXPECT_NE(ts::slurp((dir / "process.md").string()).find("| start-up |"), std::string::npos);
  fs::remove_all(dir);
}

TEST(EventCost, StepsAndEventsAgainstOneRhsEvaluation) {
  const fs::path dir = ts::scratchDir("bench", "eventcost", true);
  const auto r = bench("eventcost --scene " + ts::shellQuote(benchRig("experiment-short")) +
                           " --accuracies 1e-6 --repeat 1",
                       dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const mb::CsvTable c = table(dir / "eventcost.csv");
  ASSERT_EQ(c.rows.size(), 1u);
  EXPECT_EQ(c.text(0, "integrator"), "verner76");  // the rig's default at N = 2
  // an embedded pair of 10 stages with its interpolant: more evaluations a step than stages of a
  // plain step, fewer than two steps' worth
  EXPECT_GT(c.number(0, "evals_per_step"), 6.0);
  EXPECT_LT(c.number(0, "evals_per_step"), 20.0);
  EXPECT_GT(c.number(0, "rhs_s"), 0.0);
  // the run's evaluations take part of its time, never more than all of it
  EXPECT_GT(c.number(0, "rhs_share"), 0.0);
  EXPECT_LT(c.number(0, "rhs_share"), 1.0);
  EXPECT_NEAR(c.number(0, "step_in_rhs") * c.number(0, "rhs_s") * c.number(0, "steps"),
              c.number(0, "cpu_s"), 1e-5 * c.number(0, "cpu_s"));
  fs::remove_all(dir);
}

TEST(FitCost, EachFitAgainstOneRunOfItsRig) {
  const fs::path dir = ts::scratchDir("bench", "fitcost", true);
  // a stand-in fit bench: one record (the peer's scene, shortened), its fit "took" 2.5 s
  const fs::path fake = script(
      dir, "fit-bench.sh",
      "while [ $# -gt 0 ]; do case $1 in --keep) keep=$2;; --csv) csv=$2;; esac; shift; done\n"
      "sed 's/tau: 30/tau: 3/' '" +
          benchRig("peer-n2") +
          "' > \"$keep/record1.yaml\"\n"
          "printf "
          "'record,wall_s,cpu_s,model_runs,converged,recovered,error\\n1,2.5,2,300,1,1,\"\"\\n'"
          " > \"$csv\"\n");
  const auto r = bench("fitcost --fit-bench " + ts::shellQuote(fake.string()) + " --metrosync " +
                           ts::shellQuote(METROSYNC_BINARY) + " --records 1 --run-repeat 1",
                       dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const mb::CsvTable c = table(dir / "fit.csv");
  ASSERT_EQ(c.rows.size(), 1u);
  const double run = c.number(0, "run_wall_seconds");
  EXPECT_GT(run, 0.0);
  EXPECT_NEAR(c.number(0, "fit_over_run"), 2.5 / run, 1e-5 * 2.5 / run);
  EXPECT_NE(ts::slurp((dir / "fit.md").string()).find("median 2.5 s wall (target <= 1 s: NOT met)"),
            std::string::npos);
  fs::remove_all(dir);
}

TEST(ContinueCost, AFinishedRunAndAStoppedOne) {
  const fs::path dir = ts::scratchDir("bench", "continue", true);
  // a stand-in metrosync: three points on a rig, or a sleep on the rig named "slow"
  const fs::path fake = script(
      dir, "metrosync.sh",
      "rig=$2; while [ $# -gt 0 ]; do [ \"$1\" = --out ] && out=$2; shift; done\n"
      "case $rig in *slow*) sleep 30;; esac\n"
      "mkdir -p \"$out\" && printf 'mu,A\\n0.1,1\\n0.2,1\\n0.3,1\\n' > \"$out/branches.csv\"\n");
  const auto r = bench("continue --metrosync " + ts::shellQuote(fake.string()) +
                           " --rig fast.yaml --rig slow.yaml --timeout 1",
                       dir);
  ASSERT_EQ(r.code, 0) << r.err;  // a run stopped by --timeout is a measurement, not a failure
  const mb::CsvTable c = table(dir / "continuation.csv");
  ASSERT_EQ(c.rows.size(), 2u);
  EXPECT_EQ(c.text(0, "points"), "3");
  EXPECT_EQ(c.text(0, "timed_out"), "0");
  EXPECT_EQ(c.text(0, "failure"), "");
  EXPECT_EQ(c.text(1, "timed_out"), "1");
  EXPECT_GE(c.number(1, "wall_s"), 1.0);
  const std::string md = ts::slurp((dir / "continuation.md").string());
  EXPECT_NE(md.find("| fast.yaml | 1 |"), std::string::npos) << md;
  EXPECT_NE(md.find("NOT met (not finished in"), std::string::npos) << md;
  EXPECT_NE(md.find("--param platform.friction.mu --to 0.01 --all -q"), std::string::npos);
  fs::remove_all(dir);
}
