// The run contract for networks (SPEC "networks", issue 24): a network's `run` ends at exactly
// the requested end on both engines, its last row is the state there, and its summary.json has a
// single run's keys (`final`, `regime`, `regime_window`, `wall_seconds`, `engine_seconds`,
// `version`, `command`), with `final` per platform too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/common/run_metrosync.h"

namespace metrosync {
namespace {

using testing_support::runMetrosync;
using testing_support::scratchDir;
using testing_support::shellQuote;
using testing_support::slurp;

const std::string kRig = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/two-boards-rollers.yaml";

// The numbers of a CSV file's rows, its header left out.
std::vector<std::vector<double>> numbers(const std::string& path) {
  const auto cells = testing_support::csvRows(path);
  std::vector<std::vector<double>> rows;
  for (std::size_t r = 1; r < cells.size(); ++r) {
    std::vector<double> row;
    for (const std::string& c : cells[r]) row.push_back(std::stod(c));
    rows.push_back(row);
  }
  return rows;
}

std::string runNetwork(const std::string& name, const std::string& args) {
  const std::string out = scratchDir("netc", name);
  const auto r = runMetrosync("run " + shellQuote(kRig) + " --quiet --no-plot " + args + " --out " +
                              shellQuote(out));
  EXPECT_EQ(r.code, 0) << r.err;
  return out;
}

// The last row of every time series is at the requested end, exactly, on both engines; 3.625 s
// and 2.3 s are on no sample grid (period / 20).
TEST(NetworkContract, RunEndsAtExactlyTheRequestedEnd) {
  for (const auto& [engine, duration] :
       std::vector<std::pair<std::string, std::string>>{{"direct", "3.625"}, {"simbody", "2.3"}}) {
    const std::string out =
        runNetwork(engine, "--engine " + engine + " --set simulation.duration=" + duration);
    const double t_end = std::stod(duration);
    EXPECT_EQ(numbers(out + "/trajectory.csv").back().front(), t_end) << engine;
    EXPECT_EQ(numbers(out + "/envelope.csv").back().back(), t_end) << engine;  // t_s last
    EXPECT_EQ(numbers(out + "/order.csv").back().back(), t_end) << engine;
  }
}

// The last row is the state at the end: the same as a longer run's row at that time (a grid
// point of its samples, 29 x 0.125 s), to the runs' accuracy.
TEST(NetworkContract, LastRowIsTheStateAtTheEnd) {
  const std::string a = runNetwork("short", "--set simulation.duration=3.625");
  const std::string b =
      runNetwork("long", "--set simulation.duration=4 --set simulation.sample=0.125");
  const std::vector<double> last = numbers(a + "/trajectory.csv").back();
  std::vector<double> there;
  for (const auto& row : numbers(b + "/trajectory.csv"))
    if (row.front() == 3.625) there = row;
  ASSERT_EQ(there.size(), last.size());
  // a row is not compared with its mode columns' neighbours: angles (rad) and rates (rad/s) are
  // O(0.1-1), positions O(1e-4) m; two step sequences at the default accuracy agree to ~1e-6
  for (std::size_t k = 1; k < last.size(); ++k)
    EXPECT_NEAR(last[k], there[k], 1e-5 * (1 + std::abs(there[k]))) << "column " << k;
  // and it is not the row before: the state moved over the last sample interval
  const auto rows = numbers(a + "/trajectory.csv");
  EXPECT_GT(std::abs(rows[rows.size() - 2][7] - last[7]), 1e-4);
}

TEST(NetworkContract, SummaryHasASingleRunsKeys) {
  const std::string out = runNetwork("keys", "--set simulation.duration=3.625");
  const nlohmann::json s = nlohmann::json::parse(slurp(out + "/summary.json"));
  const std::vector<double> env = numbers(out + "/envelope.csv").back();  // tau,A1..4,psi2..4,r,t_s
  // final: the last envelope row, in the network's numbering (the CSV holds 12 digits)
  auto near = [](double a, double b) { return std::abs(a - b) <= 1e-10 * (1 + std::abs(b)); };
  ASSERT_TRUE(s.contains("final")) << s.dump();
  EXPECT_TRUE(near(s["final"]["tau"], env[0])) << s["final"]["tau"] << " " << env[0];
  ASSERT_EQ(s["final"]["A"].size(), 4u);
  ASSERT_EQ(s["final"]["psi"].size(), 3u);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(near(s["final"]["A"][i], env[1 + i])) << i;
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(near(s["final"]["psi"][i], env[5 + i])) << i;
  // per platform: its own metronomes' final amplitudes, phases relative to its first
  const nlohmann::json& a = s["final"]["A"];
  const nlohmann::json& psi = s["final"]["psi"];  // psi_2, psi_3, psi_4
  EXPECT_EQ(s["platforms"]["left"]["final"]["A"], nlohmann::json({a[0], a[1]}));
  EXPECT_EQ(s["platforms"]["right"]["final"]["A"], nlohmann::json({a[2], a[3]}));
  EXPECT_EQ(s["platforms"]["left"]["final"]["psi"][0], psi[0]);
  EXPECT_NEAR(s["platforms"]["right"]["final"]["psi"][0].get<double>(),
              psi[2].get<double>() - psi[1].get<double>(), 1e-12);
  for (const char* p : {"left", "right"}) {
    EXPECT_EQ(s["platforms"][p]["final"]["psi"].size(), 1u) << p;
    EXPECT_EQ(s["platforms"][p]["final"]["tau"], s["final"]["tau"]) << p;
  }
  // the network's label at the top, as a single run's regime
  ASSERT_TRUE(s.contains("regime"));
  EXPECT_EQ(s["regime"], s["network"]["regime"]);
  ASSERT_TRUE(s.contains("regime_window"));
  const double tau_start = s["regime_window"]["tau_start"];
  EXPECT_GT(tau_start, 0.0);
  EXPECT_LT(tau_start, env[0]);
  EXPECT_GT(s["regime_window"]["rows"].get<long>(), 0);
  for (const char* p : {"left", "right"}) {
    const double r = s["regime_window"]["platforms"][p]["r_mean"];
    EXPECT_TRUE(r >= 0 && r <= 1) << p << " " << r;
  }
  // timings and provenance as a single run's
  const double wall = s["wall_seconds"], engine = s["engine_seconds"];
  EXPECT_GT(engine, 0.0);
  EXPECT_LE(engine, wall);
  const auto v = runMetrosync("--version");
  EXPECT_NE(v.out.find(s["version"].get<std::string>()), std::string::npos) << v.out;
  EXPECT_EQ(s["command"], "run");
  // the ledger in a single run's form
  EXPECT_EQ(s["energy"]["units"], "J");
  EXPECT_LT(std::abs(s["energy"]["relative_residual"].get<double>()), 1e-6);
}

// `run` is one path for a single rig and a network: its options mean the same. --no-plot writes
// no plot (main drew order.png and raster.png anyway); without it the network's plots are there.
TEST(NetworkContract, NoPlotMeansNoPlot) {
  const std::string out = runNetwork("noplot", "--set simulation.duration=3.625");
  const nlohmann::json s = nlohmann::json::parse(slurp(out + "/summary.json"));
  for (const std::string f : s["files"]) EXPECT_EQ(f.find(".png"), std::string::npos) << f;
  for (const auto& e : std::filesystem::directory_iterator(out))
    EXPECT_NE(e.path().extension(), ".png") << e.path();
  const std::string plotted = scratchDir("netc", "plotted");
  const auto r =
      runMetrosync("run " + shellQuote(kRig) + " --quiet --set simulation.duration=3.625 --out " +
                   shellQuote(plotted));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(plotted + "/order.png"));
}

// --plot-format means the same on a network as on a single rig: its plots in that format (main
// wrote order.png and raster.png whatever was asked), named so in summary.json's files.
TEST(NetworkContract, PlotFormatMeansTheSame) {
  ASSERT_EQ(std::system("command -v gnuplot > /dev/null 2>&1"), 0)
      << "gnuplot not on PATH (tools/setup.sh installs gnuplot-nox): no run could write a plot";
  for (const std::string format : {"svg", "pdf"}) {
    const std::string out = scratchDir("netc", "format-" + format, true);
    const auto r = runMetrosync("run " + shellQuote(kRig) +
                                " --quiet --set simulation.duration=3.625 --plot-format " + format +
                                " --out " + shellQuote(out));
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json summary = nlohmann::json::parse(slurp(out + "/summary.json"));
    const std::vector<std::string> listed = summary["files"];
    for (const std::string stem : {"order.", "raster."}) {
      const std::string name = stem + format;
      EXPECT_TRUE(std::filesystem::exists(out + "/" + name)) << name;
      EXPECT_NE(std::find(listed.begin(), listed.end(), name), listed.end()) << name;
      EXPECT_FALSE(std::filesystem::exists(out + "/" + stem + "png")) << stem;
    }
    // the file is what its name says: an SVG's XML, a PDF's header
    const std::string head = slurp(out + "/order." + format).substr(0, 512);
    EXPECT_NE(head.find(format == "svg" ? "<svg" : "%PDF"), std::string::npos) << head;
  }
}

// A network of one platform (its board on a damped spring: not today's rig) is labelled by the
// single-platform rules: two identical metronomes started together stay `in-phase` (main called
// the network `synchronized`).
TEST(NetworkContract, OnePlatformIsLabelledAsASingleRig) {
  const std::string dir = scratchDir("netc", "one", true);
  const std::string metronome =
      "{box_mass: 0.0602, pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}, "
      "escapement: {angle: 0.244, steady_amplitude: 0.785}, start: {angle: 0.785, rate: 0.0}}";
  std::ofstream(dir + "/one.yaml")
      << "units: physical\nname: one-board\ngravity: 9.81\n"
      << "platforms:\n  - name: board\n    mass: 0.1432\n"
      << "    friction: {law: coulomb, mu: 6.5e-4}\n"
      << "    spring: {k: 2.0, c: 0.01}\n    metronomes:\n"
      << "      - " << metronome << "\n      - " << metronome << "\nsimulation:\n  duration: 20\n";
  const auto r = runMetrosync("run " + shellQuote(dir + "/one.yaml") + " --quiet --no-plot --out " +
                              shellQuote(dir + "/out"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json s = nlohmann::json::parse(slurp(dir + "/out/summary.json"));
  EXPECT_EQ(s["platforms"]["board"]["regime"], "in-phase");
  EXPECT_EQ(s["network"]["regime"], "in-phase");
  EXPECT_EQ(s["regime"], "in-phase");
}

// One report of every run (sim/record/run_report.h), one summary.json builder: a network's
// summary.json has every key a single rig's report gives, counts and ledger alike (main's network
// summary had no `accuracy` and no `write_seconds`), with the network's own accuracy.
TEST(NetworkContract, SummaryHasEveryKeyOfASingleRunsReport) {
  const std::string net_out =
      runNetwork("report", "--set simulation.duration=1 --set simulation.accuracy=1e-9");
  const nlohmann::json n = nlohmann::json::parse(slurp(net_out + "/summary.json"));
  const std::string single = scratchDir("netc", "report-single", true);
  const auto r = runMetrosync(
      "run " + shellQuote(std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/experiment.yaml") +
      " --model full -q --no-plot --set simulation.duration=1 --out " +
      shellQuote(single + "/out"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json s = nlohmann::json::parse(slurp(single + "/out/summary.json"));
  for (const char* key : {"model", "engine", "integrator", "accuracy", "counts", "energy",
                          "wall_seconds", "engine_seconds", "write_seconds", "complete", "command",
                          "units", "rig", "version", "regime", "regime_window", "final"}) {
    ASSERT_TRUE(s.contains(key)) << key;
    EXPECT_TRUE(n.contains(key)) << key;
  }
  for (const auto& [key, value] : s["counts"].items())
    EXPECT_TRUE(n["counts"].contains(key)) << key;
  for (const auto& [key, value] : s["energy"].items())
    EXPECT_TRUE(n["energy"].contains(key)) << key;
  EXPECT_EQ(n["accuracy"].get<double>(), 1e-9);
  EXPECT_GE(n["write_seconds"].get<double>(), 0.0);
}

// The refusal names a network of one in the singular (main said "a network of 1 platforms").
TEST(NetworkContract, ANetworkOfOneIsNamedInTheSingular) {
  const std::string dir = scratchDir("netc", "singular", true);
  std::ofstream(dir + "/one.yaml")
      << "units: physical\nname: one-board\ngravity: 9.81\n"
      << "platforms:\n  - name: board\n    mass: 0.1432\n"
      << "    friction: {law: coulomb, mu: 6.5e-4}\n"
      << "    spring: {k: 2.0, c: 0.01}\n    metronomes:\n"
      << "      - {box_mass: 0.0602, pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}, "
         "escapement: {angle: 0.244, steady_amplitude: 0.785}}\nsimulation: {duration: 2}\n";
  const auto r = runMetrosync("run " + shellQuote(dir + "/one.yaml") + " --model slow -q --out " +
                              shellQuote(dir + "/out"));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("a network of 1 platform runs the full model only"), std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("1 platforms"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
}

// SIGINT stops a network's run as it stops a single rig's (tests/cli CliInterrupted): exit 3, the
// rows written so far kept whole, summary.json says complete: false and why; no temporary file.
TEST(NetworkContract, SigintStopsTheRunAndKeepsItsRows) {
  const std::string dir = scratchDir("netc", "sigint", true), out = dir + "/out";
  const std::string script =
      shellQuote(METROSYNC_BINARY) + " run " + shellQuote(kRig) +
      " --quiet --no-plot --set simulation.duration=8000 --out " + shellQuote(out) +
      " 2>/dev/null & pid=$!; for i in $(seq 600); do ls -A " + shellQuote(out) +
      " 2>/dev/null | grep -q part && break; sleep 0.05; done; sleep 0.5; kill -" +
      std::to_string(SIGINT) + " $pid; wait $pid; echo $? > " + shellQuote(dir + "/code");
  ASSERT_EQ(std::system(("bash -c " + shellQuote(script)).c_str()), 0);
  EXPECT_EQ(std::stoi(slurp(dir + "/code")), 3);
  const nlohmann::json s = nlohmann::json::parse(slurp(out + "/summary.json"));
  EXPECT_FALSE(s["complete"].get<bool>());
  EXPECT_NE(s["failure"].get<std::string>().find("interrupted"), std::string::npos) << s["failure"];
  const auto rows = numbers(out + "/trajectory.csv");
  ASSERT_GE(rows.size(), 2u);
  for (const auto& row : rows) EXPECT_EQ(row.size(), rows.front().size());
  for (const auto& entry : std::filesystem::directory_iterator(out))
    EXPECT_EQ(entry.path().filename().string().find(".part"), std::string::npos) << entry.path();
}

}  // namespace
}  // namespace metrosync
