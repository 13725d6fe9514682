// The benchmark tool (tools/bench/): its work-precision arithmetic, the Siconos peer's convergence
// on a short scene, and metrosync_bench end to end on a tiny scene (a few seconds). Timings are
// the benchmark's business, not the tests': nothing here checks a wall time.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tools/bench/bench_metrics.h"
#include "tools/bench/bench_report.h"
#include "tools/bench/bench_run.h"
#include "tools/bench/siconos_peer.h"
#include "tools/bench/wp_csv.h"

namespace mb = metrosync::bench;
namespace fs = std::filesystem;

namespace {

// The default rig (yaml/rigs/bench/experiment.yaml) cut to `seconds`.
mb::Scene shortExperiment(double seconds) {
  return mb::loadScene(std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/bench/experiment.yaml",
                       {"simulation.duration=" + std::to_string(seconds)});
}

std::string readFile(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

int countLines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

}  // namespace

TEST(BenchMetrics, FrontKeepsTheCheapestRunForEachError) {
  // (error, time): the third point is dominated by the second (more accurate and cheaper)
  const auto front = mb::paretoFront({{1e-2, 1.0}, {1e-4, 2.0}, {1e-3, 3.0}, {1e-6, 8.0}});
  ASSERT_EQ(front.size(), 3u);
  EXPECT_EQ(front[0].error, 1e-6);
  EXPECT_EQ(front[1].error, 1e-4);
  EXPECT_EQ(front[2].error, 1e-2);
}

TEST(BenchMetrics, TimeAtErrorIsLogLogLinearAndNeverExtrapolates) {
  const auto front = mb::paretoFront({{1e-6, 8.0}, {1e-2, 2.0}});
  // halfway in log(error) between the two: geometric mean of the times
  EXPECT_NEAR(mb::timeAtError(front, 1e-4), 4.0, 1e-12);
  EXPECT_NEAR(mb::timeAtError(front, 1e-6), 8.0, 1e-12);
  EXPECT_TRUE(std::isnan(mb::timeAtError(front, 1e-7)));
  EXPECT_TRUE(std::isnan(mb::timeAtError(front, 1e-1)));
}

TEST(BenchMetrics, RatiosOnTheOverlapOnly) {
  const auto a = mb::paretoFront({{1e-8, 1.0}, {1e-3, 0.1}});
  const auto b = mb::paretoFront({{1e-5, 100.0}, {1e-1, 10.0}});
  const auto r = mb::ratiosAtEqualError(a, b);
  ASSERT_FALSE(r.empty());
  EXPECT_NEAR(r.front().error, 1e-5, 1e-18);
  EXPECT_NEAR(r.back().error, 1e-3, 1e-15);
  for (const auto& x : r) EXPECT_LT(x.ratio(), 1.0);
  EXPECT_TRUE(mb::ratiosAtEqualError(a, mb::paretoFront({{1e-2, 1.0}, {1e-1, 0.5}})).empty());
}

TEST(BenchReport, TheVerdictReadsTheRecordsCsvBack) {
  // what precision writes (recordsCsv) is what the verdict reads (parseWorkPrecisionCsv): every
  // field it needs by its header name, quoting included
  auto record = [](const std::string& spec, const std::string& status, double err_env,
                   double err_final, double cpu_s, int runs) {
    mb::Record r;
    r.scene = "s";
    r.n_metronomes = 3;
    r.periods = 12.5;
    r.method = mb::parseMethod(spec);
    r.status = status;
    r.note = "a note, with a comma";
    r.runs = runs;
    r.cpu_median_s = cpu_s;
    r.wall_median_s = 2 * cpu_s;
    r.load_min = 1.25;
    r.load_max = 2.5;
    r.error.envelope = err_env;
    r.error.final_state = err_final;
    r.error.rows = 10;
    return r;
  };
  const std::vector<mb::Record> recs = {
      record("direct:verner76:1e-13", "reference", 0, 0, 0.5, 1),
      record("simbody:rk-merson:1e-12", "cross-check", 2.5e-10, 7.5e-9, 0.5, 1),
      record("direct:dopri5:1e-6", "ok", 1.5e-7, 3.25e-6, 0.00125, 5),
      record("simbody:rk-merson:1e-6", "ok", 2.5e-6, 4.5e-5, 0.75, 4),
      record("direct:verner65:1e-12", "skipped (predicted over budget)", 0, 0, 0, 0)};
  const auto scenes =
      mb::parseWorkPrecisionCsv(mb::recordsCsv(recs), "wp-s.csv", mb::Sides{"direct", "simbody"});
  ASSERT_EQ(scenes.size(), 1u);
  const mb::VerdictScene& s = scenes[0];
  EXPECT_EQ(s.n, 3);
  EXPECT_DOUBLE_EQ(s.periods, 12.5);
  ASSERT_EQ(s.ours.size(), 1u);
  ASSERT_EQ(s.peer.size(), 1u);
  EXPECT_DOUBLE_EQ(s.ours[0].err_envelope, 1.5e-7);
  EXPECT_DOUBLE_EQ(s.ours[0].err_final, 3.25e-6);
  EXPECT_DOUBLE_EQ(s.ours[0].cpu_s, 0.00125);
  EXPECT_DOUBLE_EQ(s.ours[0].wall_s, 0.0025);
  EXPECT_EQ(s.ours[0].runs, 5);
  EXPECT_EQ(s.peer[0].method, "simbody:rk-merson:1e-06");
  EXPECT_EQ(s.peer[0].runs, 4);
  EXPECT_DOUBLE_EQ(s.load_min, 1.25);
  const auto ag = mb::peerAgreement(scenes, mb::Sides{"direct", "simbody"});
  ASSERT_EQ(ag.size(), 1u);
  EXPECT_TRUE(ag[0].validated);
  EXPECT_EQ(ag[0].reference, "direct:verner76:1e-13");
  EXPECT_DOUBLE_EQ(ag[0].err_final, 7.5e-9);
  EXPECT_FALSE(ag[0].flagged());
}

TEST(BenchRun, EnginesAgreeOnAShortScene) {
  const mb::Scene scene = shortExperiment(3.0);
  const mb::RunResult ref = mb::runOnce(scene, mb::parseMethod("direct:verner76:1e-11"), 0);
  ASSERT_TRUE(ref.complete);
  const mb::RunResult sb = mb::runOnce(scene, mb::parseMethod("simbody:rk-merson:1e-9"), 0);
  ASSERT_TRUE(sb.complete);
  const mb::ErrorVsRef e = mb::compareRuns(sb, ref);
  EXPECT_EQ(e.rows, static_cast<long>(ref.envelope.size()));
  EXPECT_GT(e.rows, 5);
  // both engines integrate e1.1a-c to ~1e-9 relative local error: their envelopes agree far
  // below the envelope's own ripple (O(epsilon) = 0.07)
  EXPECT_LT(e.envelope, 1e-5);
  EXPECT_LT(e.final_state, 1e-4);
  EXPECT_EQ(sb.ticks, ref.ticks);
}

TEST(BenchRun, SiconosPeerConvergesAtFirstOrder) {
  if (!mb::siconosAvailable()) GTEST_SKIP() << "built without Siconos";
  const mb::Scene scene = shortExperiment(3.0);
  const mb::RunResult ref = mb::runOnce(scene, mb::parseMethod("direct:verner76:1e-11"), 0);
  double err[2];
  const double steps[2] = {128, 1024};
  for (int k = 0; k < 2; ++k) {
    mb::Method m = mb::parseMethod("siconos:moreau-jean");
    m.steps_per_period = steps[k];
    const mb::RunResult r = mb::runOnce(scene, m, 0);
    ASSERT_TRUE(r.complete) << r.failure;
    EXPECT_EQ(r.ticks, ref.ticks);
    err[k] = mb::compareRuns(r, ref).envelope;
  }
  // 8 times smaller steps: the error falls by about 8 (first order); at least by 4
  EXPECT_LT(err[1], err[0] / 4) << err[0] << " " << err[1];
  EXPECT_LT(err[1], 2e-2);
}

TEST(BenchTool, RunsEndToEndOnATinyScene) {
  const fs::path out =
      fs::temp_directory_path() / ("metrosync-bench-test-" + std::to_string(::getpid()));
  fs::remove_all(out);
  const std::string rig = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/bench/experiment.yaml";
  std::string cmd = std::string("'") + METROSYNC_BENCH_BINARY + "' precision --scene '" + rig +
                    "' --set simulation.duration=2 --methods direct:verner65,simbody:rk-merson" +
                    (mb::siconosAvailable() ? ",siconos:moreau-jean" : "") +
                    " --accuracies 1e-5,1e-7 --simbody-accuracies 1e-5 --siconos-steps 64,128 "
                    "--reference "
                    "direct:verner76:1e-11 --cross-check direct:dopri5:1e-11 --repeat 2 "
                    "--max-load 0 --quiet --out '" +
                    out.string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const std::string csv = readFile(out / "wp-experiment.csv");
  // header, reference, cross-check, 2 direct + 1 simbody (+ 2 siconos) points
  EXPECT_EQ(countLines(csv), 1 + 2 + 3 + (mb::siconosAvailable() ? 2 : 0)) << csv;
  EXPECT_EQ(csv.find("simbody,rk-merson,1e-07"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",reference,"), std::string::npos);
  EXPECT_NE(csv.find(",cross-check,"), std::string::npos);
  EXPECT_EQ(csv.find(",failed,"), std::string::npos) << csv;
  EXPECT_TRUE(fs::exists(out / "wp-experiment.md"));
  EXPECT_TRUE(fs::exists(out / "wp-experiment-equal-error.csv"));

  cmd = std::string("'") + METROSYNC_BENCH_BINARY +
        "' nscale --n 1,3 --periods 2 --methods direct:verner65:1e-8,simbody:rk-merson:1e-8 "
        "--repeat 1 --max-load 0 --quiet --out '" +
        out.string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  EXPECT_EQ(countLines(readFile(out / "nscale.csv")), 1 + 4);
  EXPECT_TRUE(fs::exists(out / "nscale.md"));
  fs::remove_all(out);
}
