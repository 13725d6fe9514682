// The whole process's breakdown (tools/bench/process_phases.h): the phase lines `metrosync run`
// prints with METROSYNC_PHASES=1 read back, the start-up and the exit from the parent's clock,
// the parts tiling the process, and the budget 1.5 x wall_seconds + 3 ms. No process
// runs here: synthetic lines and clocks.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "tools/bench/process_phases.h"

namespace mb = metrosync::bench;

namespace {

// The lines of one run whose main starts at `main_at` (seconds) with phases of these lengths (ms).
std::string phaseLines(double main_at, const std::vector<std::pair<std::string, double>>& p) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "metrosync: phase main at %.9f s\n", main_at);
  std::string s = std::string("some other line\n") + buf;
  double at = main_at;
  for (const auto& [name, ms] : p) {
    at += 1e-3 * ms;
    std::snprintf(buf, sizeof buf, "metrosync: phase %s %.3f ms (at %.9f s)\n", name.c_str(), ms,
                  at);
    s += buf;
  }
  return s;
}

std::string parseError(const std::string& text) {
  try {
    mb::parsePhases(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ProcessPhases, ReadsTheLinesTheProgramPrints) {
  const mb::PhaseMarks m =
      mb::parsePhases(phaseLines(100.0, {{"args", 1.5}, {"rig", 0.25}, {"run", 12.0}}));
  EXPECT_DOUBLE_EQ(m.main_at, 100.0);
  ASSERT_EQ(m.names, (std::vector<std::string>{"args", "rig", "run"}));
  EXPECT_DOUBLE_EQ(m.ms[2], 12.0);
  EXPECT_NEAR(m.last_at, 100.01375, 1e-9);
  EXPECT_NE(parseError("no phases at all\n").find("no phase line"), std::string::npos);
  EXPECT_NE(parseError("metrosync: phase args 1.0 ms (at 3 s)\n").find("not 'main at T s'"),
            std::string::npos);
  EXPECT_NE(parseError(phaseLines(1, {}) + "metrosync: phase run -2 ms (at 3 s)\n")
                .find("not 'NAME MS ms (at T s)'"),
            std::string::npos);
}

TEST(ProcessPhases, TheStartUpAndTheExitComeFromOutsideAndThePartsTileTheProcess) {
  // three runs: start-up 4, 5, 9 ms; the phases 1 + 20 ms; the exit 2, 3, 1 ms
  std::vector<mb::ProcessSample> runs;
  const double startup[] = {4, 5, 9}, exit_ms[] = {2, 3, 1}, run_ms[] = {20, 20, 26};
  for (int k = 0; k < 3; ++k) {
    mb::ProcessSample s;
    s.start_s = 50.0 + k;
    s.marks = mb::parsePhases(
        phaseLines(s.start_s + 1e-3 * startup[k], {{"args", 1.0}, {"run", run_ms[k]}}));
    s.end_s = s.marks.last_at + 1e-3 * exit_ms[k];
    s.wall_seconds = 0.018;
    s.cpu_s = 0.02;
    runs.push_back(s);
  }
  const mb::ProcessBreakdown b = mb::processBreakdown(runs);
  ASSERT_EQ(b.phases, (std::vector<std::string>{"start-up", "args", "run", "exit"}));
  EXPECT_NEAR(b.ms[0], 5.0, 1e-6);  // the medians
  EXPECT_NEAR(b.ms[2], 20.0, 1e-6);
  EXPECT_NEAR(b.ms[3], 2.0, 1e-6);
  EXPECT_NEAR(b.total_ms, 29.0, 1e-6);  // the median of the runs' totals 27, 29, 37
  EXPECT_NEAR(b.unaccounted_ms, 0.0, 1e-6);
  // the budget: 1.5 x 18 ms + 3 ms = 30 ms; the median process, 29 ms, is within it
  EXPECT_NEAR(b.budget_ms, 30.0, 1e-9);
  EXPECT_TRUE(b.met());
  EXPECT_NE(mb::processMarkdown(b, "").find("met**"), std::string::npos);
  runs[0].wall_seconds = runs[1].wall_seconds = runs[2].wall_seconds = 0.01;  // budget 18 ms
  const mb::ProcessBreakdown over = mb::processBreakdown(runs);
  EXPECT_FALSE(over.met());
  EXPECT_NE(mb::processMarkdown(over, "").find("NOT met** (over by 11 ms, 1.61x)"),
            std::string::npos)
      << mb::processMarkdown(over, "");
  const std::string csv = mb::processCsv(b, "peer-n2", 0.5, 0.7);
  EXPECT_NE(csv.find("start-up_ms,args_ms,run_ms,exit_ms\npeer-n2,3,29,18,30,20,"),
            std::string::npos)
      << csv;
  EXPECT_NE(csv.find(",0.50,0.70,5,1,20,2\n"), std::string::npos) << csv;
}

TEST(ProcessPhases, RunsWithDifferentPhasesAreNotMixed) {
  mb::ProcessSample a, b;
  a.marks = mb::parsePhases(phaseLines(1, {{"args", 1}}));
  b.marks = mb::parsePhases(phaseLines(1, {{"rig", 1}}));
  EXPECT_THROW(mb::processBreakdown({a, b}), std::invalid_argument);
  EXPECT_THROW(mb::processBreakdown({}), std::invalid_argument);
}
