// `metrosync sweep` over a coupling of a network of platforms (docs/networks.md): the network's
// label per grid point, checked against independent truth (two detuned metronomes on uncoupled
// boards cannot lock; boards joined by a stiff spring are one board, whose two metronomes lock)
// and against `metrosync run` of the same point; a 2-D map; --resume after a kill.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/common/run_metrosync.h"

namespace metrosync {
namespace {

using testing_support::runMetrosync;
using testing_support::scratchDir;
using testing_support::shellQuote;
using testing_support::slurp;

// Two boards on viscous rollers, one metronome each, the right one's pendulum 7% longer (its
// frequency ~3% lower): over the label's window (the last 4 s of 40, ~13 periods) uncoupled
// phases drift apart by ~2 rad, far beyond the 0.5 rad of "locked".
std::string pairRig(const std::string& dir) {
  const std::string path = dir + "/pair.yaml";
  std::ofstream(path) << R"(units: physical
name: pair
platforms:
  - name: left
    mass: 0.1432
    friction: {law: viscous, c: 0.05}
    metronomes:
      - {box_mass: 0.0602, pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}, escapement: {angle: 0.244, steady_amplitude: 0.785}, start: {angle: 0.785, rate: 0}}
  - name: right
    mass: 0.1432
    friction: {law: viscous, c: 0.05}
    metronomes:
      - {box_mass: 0.0602, pendulum: {mass: 0.0226, length: 0.024, decay_rate: 0.5}, escapement: {angle: 0.244, steady_amplitude: 0.785}, start: {angle: 0.3, rate: -2.0}}
couplings:
  - {between: [left, right], k: 2.0}
simulation: {duration: 40}
)";
  return path;
}

std::vector<std::vector<std::string>> rows(const std::string& csv) {
  std::vector<std::vector<std::string>> out;
  std::istringstream in(slurp(csv));
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    out.push_back(cells);
  }
  return out;
}

int column(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t k = 0; k < header.size(); ++k)
    if (header[k] == name) return static_cast<int>(k);
  ADD_FAILURE() << "no column " << name;
  return 0;
}

TEST(NetworkSweep, CouplingMapGivesTheNetworkLabelOfEachRun) {
  const std::string d = scratchDir("netsweep", "k", true);
  const std::string rig = pairRig(d);
  const auto r =
      runMetrosync("sweep " + shellQuote(rig) +
                   " --vary couplings.0.k=0:1000:3 --jobs 2 -q --out " + shellQuote(d + "/sweep"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto t = rows(d + "/sweep/regimes.csv");
  ASSERT_EQ(t.size(), 4u);
  const std::vector<std::string>& h = t[0];
  EXPECT_EQ(h[0], "couplings.0.k");
  const int regime = column(h, "regime"), rr = column(h, "r"), clusters = column(h, "clusters");
  // independent truth: uncoupled detuned metronomes drift; a stiff spring makes one board
  EXPECT_EQ(t[1][regime], "disordered");
  EXPECT_TRUE(t[3][regime] == "synchronized" || t[3][regime] == "antiphase-groups") << t[3][regime];
  EXPECT_EQ(t[1][clusters].find("left="), 0u) << t[1][clusters];
  // each point is what `metrosync run` says of the same rig with that k
  for (int row : {1, 3}) {
    const std::string out = d + "/run" + std::to_string(row);
    const auto run =
        runMetrosync("run " + shellQuote(rig) + " -q --set couplings.0.k=" + t[row][0] + " --out " +
                     shellQuote(out));
    ASSERT_EQ(run.code, 0) << run.err;
    const nlohmann::json s = nlohmann::json::parse(slurp(out + "/summary.json"));
    EXPECT_EQ(s["network"]["regime"].get<std::string>(), t[row][regime]) << "k = " << t[row][0];
    EXPECT_NEAR(s["network"]["r"].get<double>(), std::stod(t[row][rr]), 1e-11);
  }
  const nlohmann::json m = nlohmann::json::parse(slurp(d + "/sweep/sweep.json"));
  EXPECT_EQ(m["model"], "full");
  EXPECT_EQ(m["engine"], "direct");
  EXPECT_TRUE(m["complete"].get<bool>());
  // timings.csv: a network's point has its engine's CPU seconds as a rig's has, inside its own
  const auto timing = rows(d + "/sweep/timings.csv");
  ASSERT_EQ(timing.size(), 4u);
  for (std::size_t k = 1; k < timing.size(); ++k) {
    ASSERT_EQ(timing[k].size(), 4u) << "row " << k << ": an empty engine_cpu_seconds";
    const double cpu = std::stod(timing[k][2]), engine = std::stod(timing[k][3]);
    EXPECT_GT(engine, 0.0) << "row " << k;
    EXPECT_LE(engine, cpu) << "row " << k;
  }
}

// SIGINT stops a network sweep inside its running point, as a rig's sweep: two points of a
// long run (200000 s, ~30 s each here) and SIGINT after 3 s: exit 3, no point done (the running
// one interrupted, not finished first), sweep.json says so and --resume is offered.
TEST(NetworkSweep, SigintInterruptsTheRunningPoint) {
  const std::string d = scratchDir("netsweep", "sigint", true);
  testing_support::RunIn in;
  in.env = "timeout --foreground --preserve-status -s INT 3";  // one signal: see test_big_sweep.cpp
  const auto r = runMetrosync("sweep " + shellQuote(pairRig(d)) +
                                  " --vary couplings.0.k=0:10:2 --set simulation.duration=200000"
                                  " --jobs 1 -q --no-plot --out " +
                                  shellQuote(d + "/sweep"),
                              in);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("--resume"), std::string::npos) << r.err;
  const nlohmann::json m = nlohmann::json::parse(slurp(d + "/sweep/sweep.json"));
  EXPECT_TRUE(m["interrupted"].get<bool>());
  EXPECT_EQ(m["points"]["done"].get<long>(), 0);
}

TEST(NetworkSweep, TwoKeysMakeAMapAndTheSlowFlowIsRefused) {
  const std::string d = scratchDir("netsweep", "map", true);
  const std::string rig = pairRig(d);
  const auto r = runMetrosync("sweep " + shellQuote(rig) +
                              " --vary couplings.0.k=0:1000:2 --vary couplings.0.c=0:0.01:2 "
                              "--set simulation.duration=10 --jobs 2 -q --out " +
                              shellQuote(d + "/map"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto t = rows(d + "/map/regimes.csv");
  ASSERT_EQ(t.size(), 5u);
  EXPECT_EQ(t[0][1], "couplings.0.c");
  for (std::size_t k = 1; k < t.size(); ++k) EXPECT_NE(t[k][2], "failed") << k;
  const auto slow =
      runMetrosync("sweep " + shellQuote(rig) + " --vary couplings.0.k=0:1:2 --model slow --out " +
                   shellQuote(d + "/slow"));
  EXPECT_EQ(slow.code, 2);
  EXPECT_NE(slow.err.find("a network of 2 platforms"), std::string::npos) << slow.err;
  EXPECT_FALSE(std::filesystem::exists(d + "/slow"));
}

TEST(NetworkSweep, ResumeAfterAKillGivesTheSameTable) {
  const std::string d = scratchDir("netsweep", "resume", true);
  const std::string args = "sweep " + shellQuote(pairRig(d)) +
                           " --vary couplings.0.k=0:1000:4 --set simulation.duration=10 "
                           "--jobs 1 -q --out ";
  ASSERT_EQ(runMetrosync(args + shellQuote(d + "/whole")).code, 0);
  testing_support::RunIn killed;
  killed.env = "METROSYNC_SWEEP_STOP_AFTER=2";
  EXPECT_EQ(runMetrosync(args + shellQuote(d + "/cut"), killed).code, 137);
  EXPECT_EQ(rows(d + "/cut/regimes.csv").size(), 3u);  // the header and two points
  ASSERT_EQ(runMetrosync(args + shellQuote(d + "/cut") + " --resume").code, 0);
  EXPECT_EQ(slurp(d + "/cut/regimes.csv"), slurp(d + "/whole/regimes.csv"));
}

}  // namespace
}  // namespace metrosync
