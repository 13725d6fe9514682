// timings.csv (tools/report/sweep_files.h) and where a sweep spends its time outside the points:
// every point's wall, CPU and engine CPU seconds, nested as they are measured; an older timings.csv
// resumed in the new layout; maps drawn only after the last point, and never with --no-plot.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "tests/common/run_metrosync.h"
#include "tools/report/sweep_files.h"

namespace {

namespace fs = std::filesystem;
using metrosync::testing_support::CommandResult;
using metrosync::testing_support::shellQuote;
using metrosync::testing_support::slurp;

std::string scratch(const std::string& name) {
  return metrosync::testing_support::scratchDir("sweep_timings", name, true);
}

CommandResult metrosync(const std::string& args, const std::string& env = "") {
  return metrosync::testing_support::runMetrosync(args, {"", env});
}

std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> v;
  for (std::string l; std::getline(in, l);) v.push_back(l);
  return v;
}

// The cells of a line, empty ones included ("1,,"" has three).
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> v(1);
  for (char c : line) {
    if (c == ',')
      v.emplace_back();
    else
      v.back().push_back(c);
  }
  return v;
}

std::string pairRig(const std::string& dir) {
  return metrosync::testing_support::writePairRig(dir, 40);
}

const std::string kGrid =
    " --vary metronomes.0.start.phi=0:2pi:6:open --vary platform.friction.mu=0:0.8:5";

// Checks timings.csv of a finished 30-point sweep: every index once, engine CPU within the point's
// CPU (both from the thread's clock, one interval inside the other). Returns the rows by index.
std::map<long, std::vector<std::string>> checkTimings(const std::string& path, size_t rows) {
  const auto l = lines(path);
  EXPECT_EQ(l.size(), rows + 1);
  EXPECT_EQ(l.at(0), "index,wall_seconds,cpu_seconds,engine_cpu_seconds");
  std::map<long, std::vector<std::string>> by_index;
  for (size_t k = 1; k < l.size(); ++k) {
    const auto c = cells(l[k]);
    EXPECT_EQ(c.size(), 4u) << l[k];
    EXPECT_TRUE(by_index.emplace(std::stol(c.at(0)), c).second) << "twice: " << l[k];
  }
  return by_index;
}

TEST(SweepTimings, EveryPointHasItsWallCpuAndEngineSeconds) {
  for (const char* model : {"slow", "full"}) {
    const std::string d = scratch(std::string("both_") + model);
    const CommandResult r = metrosync("sweep " + shellQuote(pairRig(d)) + kGrid + " --model " +
                                          model + " -q --no-plot --out " + d + "/out",
                                      "METROSYNC_SWEEP_FAIL_AT=4");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto rows = checkTimings(d + "/out/timings.csv", 30);
    ASSERT_EQ(rows.size(), 30u);
    double cpu = 0.0, engine = 0.0;
    for (const auto& [g, c] : rows) {
      const double wall_s = std::stod(c[1]), cpu_s = std::stod(c[2]), engine_s = std::stod(c[3]);
      EXPECT_GT(wall_s, 0.0) << g;
      EXPECT_GT(cpu_s, 0.0) << g;
      EXPECT_GE(engine_s, 0.0) << g;
      EXPECT_LE(engine_s, cpu_s) << g << " (" << model << ")";
      cpu += cpu_s;
      engine += engine_s;
    }
    // the injected failure ran no engine at all
    EXPECT_LT(std::stod(rows.at(4)[3]), 1e-3);
    // the engine is where a point's time goes (a loose bound: timings are not tested here)
    EXPECT_GT(engine, 0.5 * cpu) << model;
  }
}

TEST(SweepTimings, AnOlderTimingsFileIsRewrittenInTheNewLayout) {
  const std::string d = scratch("old_layout");
  const std::string path = d + "/timings.csv";
  EXPECT_EQ(metrosync::resumableTimingsBytes(path), 0u);  // none: start afresh
  // the layout before cpu_seconds, with a last line cut short
  std::ofstream(path) << "index,wall_seconds\n3,0.5\n7,0.25\n1,0.";
  const size_t keep = metrosync::resumableTimingsBytes(path);
  const std::string want = metrosync::timingsHeader() + "\n3,0.5,,\n7,0.25,,\n";
  EXPECT_EQ(slurp(path), want);
  EXPECT_EQ(keep, want.size());
  // a file of this layout is kept as it is, up to its last whole line
  std::ofstream(path) << want << "9,0.1,0.1";
  EXPECT_EQ(metrosync::resumableTimingsBytes(path), want.size());
  EXPECT_EQ(slurp(path), want + "9,0.1,0.1");
  // a row: empty where a time is unknown
  metrosync::SweepPoint p;
  p.index = 12;
  p.wall_seconds = 0.25;
  p.cpu_seconds = 0.125;
  EXPECT_EQ(metrosync::formatTimingsRow(p), "12,0.25,0.125,");
}

TEST(SweepTimings, AResumedSweepKeepsTheTimingsOfAnOlderLayout) {
  const std::string d = scratch("resume");
  const std::string args = "sweep " + shellQuote(pairRig(d)) + kGrid + " -q --no-plot --out " + d;
  const CommandResult cut = metrosync(args + "/out", "METROSYNC_SWEEP_STOP_AFTER=7");
  ASSERT_EQ(cut.code, 137) << cut.err;
  // as an older metrosync would have left it: index and wall seconds only
  std::string old = "index,wall_seconds\n";
  const auto l = lines(d + "/out/timings.csv");
  ASSERT_EQ(l.size(), 8u);
  for (size_t k = 1; k < l.size(); ++k) old += cells(l[k])[0] + "," + cells(l[k])[1] + "\n";
  std::ofstream(d + "/out/timings.csv", std::ios::trunc) << old;
  const CommandResult res = metrosync(args + "/out --resume");
  ASSERT_EQ(res.code, 0) << res.err;
  const auto rows = checkTimings(d + "/out/timings.csv", 30);
  long old_rows = 0;
  for (const auto& [g, c] : rows) old_rows += c[2].empty() && c[3].empty();
  EXPECT_EQ(old_rows, 7);
}

// A fake gnuplot that notes how many lines regimes.csv has when it is called.
std::string fakeGnuplot(const std::string& dir, const std::string& regimes) {
  const std::string bin = dir + "/bin";
  fs::create_directories(bin);
  std::ofstream(bin + "/gnuplot") << "#!/bin/sh\nwc -l < " << shellQuote(regimes) << " >> "
                                  << shellQuote(dir + "/calls") << "\n";
  ::chmod((bin + "/gnuplot").c_str(), 0755);
  return "PATH=" + shellQuote(bin) + ":/usr/bin:/bin";
}

TEST(SweepTimings, MapsAreDrawnAfterTheLastPointAndNeverWithNoPlot) {
  const std::string d = scratch("plots");
  const std::string rig = pairRig(d);
  const std::string env = fakeGnuplot(d, d + "/out/regimes.csv");
  CommandResult r =
      metrosync("sweep " + shellQuote(rig) + kGrid + " -q --no-plot --out " + d + "/out", env);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(d + "/calls")) << slurp(d + "/calls");
  r = metrosync("sweep " + shellQuote(rig) + kGrid + " -q --out " + d + "/out", env);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto calls = lines(d + "/calls");
  ASSERT_FALSE(calls.empty());  // the maps (the fake writes no picture: warnings on stderr)
  for (const auto& c : calls) EXPECT_EQ(std::stol(c), 31) << "a map drawn before the last point";
}

}  // namespace
