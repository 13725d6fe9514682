// `metrosync run` against the careful peer and against its engine (tools/bench/run_verdict.h):
// the run side's ratio tables beside the engine's at equal final-state error on the wall clock,
// each run point beside the engine's time with recording off at the same integrator and accuracy,
// and the run rows of precision's CSV read back. Synthetic points, no simulation.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tools/bench/peer_verdict_report.h"
#include "tools/bench/run_verdict.h"
#include "tools/bench/wp_csv.h"

namespace mb = metrosync::bench;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Points of `engine:integrator` at errors 1e-4 ... 1e-11, time scale * (1e-4 / error)^0.1 on
// both clocks (the runs without samples too).
std::vector<mb::SidePoint> points(const std::string& label, double scale) {
  std::vector<mb::SidePoint> v;
  for (int k = 4; k <= 11; ++k) {
    const double e = std::pow(10.0, -k), t = scale * std::pow(1e-4 / e, 0.1);
    char setting[16];
    std::snprintf(setting, sizeof setting, "%.0e", e);
    mb::SidePoint p{label + ":" + setting, e, kNaN, t, t, 7};
    p.cpu_final_s = p.wall_final_s = t;
    v.push_back(p);
  }
  return v;
}

mb::VerdictScene scene(const std::string& name, int n, bool with_run) {
  mb::VerdictScene s;
  s.name = name;
  s.n = n;
  s.periods = 65;
  s.ours = points("direct:verner76", 1e-3);  // 4x faster than the peer
  s.peer = points("peer:rkf78", 4e-3);
  s.our_methods = {"direct:verner76"};
  s.peer_methods = {"peer:rkf78"};
  if (with_run) {
    s.run = points("run:verner76", 8e-3);  // twice the peer's time
    for (mb::SidePoint& p : s.run)
      p.cpu_s = p.cpu_final_s = kNaN, p.engine_s = 5e-3, p.wall_over_engine = p.wall_s / 5e-3;
    s.run_methods = {"run:verner76"};
  }
  return s;
}

}  // namespace

TEST(RunVerdict, EachRunPointBesideTheEngineAloneAtTheSameSetting) {
  mb::VerdictScene s = scene("peer-n2", 2, true);
  s.ours.pop_back();  // the engine has no point at 1e-11
  const std::vector<mb::RunOverhead> o = mb::runOverheads({s, scene("no-run", 2, false)});
  ASSERT_EQ(o.size(), 8u);  // the run points of the one scene that has them
  EXPECT_EQ(o[0].method, "run:verner76:1e-04");
  EXPECT_DOUBLE_EQ(o[0].alone_s, 1e-3);  // direct:verner76:1e-04's wall without samples
  EXPECT_DOUBLE_EQ(o[0].overAlone(), 8.0);
  EXPECT_DOUBLE_EQ(o[0].wall_over_engine, 8e-3 / 5e-3);
  EXPECT_TRUE(std::isnan(o[7].alone_s));  // 1e-11: not measured on the engine's side
  const std::string csv = mb::runPointsCsv(o);
  EXPECT_NE(csv.find("peer-n2,run:verner76:1e-04,0.008,0.005,1.6,0.001,8,1.15\n"),
            std::string::npos)
      << csv;
  EXPECT_NE(mb::runPointsMarkdown(o).find("| **8.00** |"), std::string::npos);
}

TEST(RunVerdict, RunAgainstThePeerBesideTheEngineOnTheWallClock) {
  const std::vector<mb::VerdictScene> scenes = {scene("peer-n2", 2, true),
                                                scene("peer-n8", 8, false)};
  EXPECT_EQ(mb::runAsOurs(scenes).size(), 1u);
  const mb::RunVerdictText v = mb::runVerdict(scenes, {1e-5, 1e-6, 1e-7, 1e-8, 1e-9});
  // the peer takes half `run`'s time at every error: 0.50x; the engine: 4.00x
  EXPECT_NE(v.line.find("NOT MET: below 2.0 in 5 of 5 cells (worst 0.50, peer-n2 at"),
            std::string::npos)
      << v.line;
  EXPECT_NE(v.markdown.find("| peer-n2 | 2 | 4.00 / **0.50** | 4.00 / **0.50** |"),
            std::string::npos)
      << v.markdown;
  int rows = 0;
  for (size_t at = 0; (at = v.csv_rows.find(",run\n", at)) != std::string::npos; ++at) ++rows;
  EXPECT_EQ(rows, 5);
  EXPECT_NE(v.csv_rows.find("final-state,wall,peer-n2,2,1e-05,"), std::string::npos);
  // no run point: nothing at all
  EXPECT_TRUE(mb::runVerdict({scene("peer-n8", 8, false)}, {1e-5}).line.empty());
  // the pages: the run verdict first in verdicts.md, its rows in ratios.csv with side "run"
  const mb::VerdictPages p = mb::verdictPages(scenes, mb::VerdictOptions{});
  EXPECT_EQ(p.run_verdict_line, v.line);
  EXPECT_EQ(p.verdicts_markdown.find("## `metrosync run` against the peer"), 0u);
  EXPECT_NE(p.ratios_csv.find(",side\n"), std::string::npos);
  EXPECT_NE(p.ratios_csv.find(",engine\n"), std::string::npos);
}

TEST(RunVerdict, ThePrecisionCsvsRunRowsAreRead) {
  const std::string text =
      "scene,n,periods,engine,integrator,setting,status,runs,wall_median_s,cpu_median_s,"
      "load1_min,load1_max,err_envelope,err_final_state,wall_final_median_s,cpu_final_median_s,"
      "engine_median_s,wall_over_engine\n"
      "peer-n2,2,65,direct,verner76,1e-08,ok,7,0.004,0.003,1,2,1e-9,6.8e-09,0.002,0.0017,,\n"
      "peer-n2,2,65,run,verner76,1e-08,ok,7,0.009,,1,2,,6.8e-09,0.009,,0.006,1.5\n";
  const auto scenes = mb::parseWorkPrecisionCsv(text, "wp-peer-n2.csv");
  ASSERT_EQ(scenes.size(), 1u);
  ASSERT_EQ(scenes[0].run.size(), 1u);
  EXPECT_EQ(scenes[0].ours.size(), 1u);
  EXPECT_EQ(scenes[0].run[0].method, "run:verner76:1e-08");
  EXPECT_DOUBLE_EQ(scenes[0].run[0].engine_s, 0.006);
  EXPECT_DOUBLE_EQ(scenes[0].run[0].wall_over_engine, 1.5);
  EXPECT_TRUE(std::isnan(scenes[0].run[0].cpu_s));
  EXPECT_EQ(scenes[0].run_methods, (std::vector<std::string>{"run:verner76"}));
}
