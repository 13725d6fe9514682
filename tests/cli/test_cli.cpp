// End-to-end tests of the `metrosync` binary (SPEC sections 2, 3, 5): exit codes, what is (not)
// written, the files' headers and the summary's keys. Each test runs the built binary.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "base/constants.h"
#include "sim/engines/simbody/simbody_engine.h"
#include "sim/record/envelope.h"
#include "sim/record/envelope_csv.h"
#include "tests/common/run_metrosync.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using Result = metrosync::testing_support::CommandResult;
using metrosync::testing_support::slurp;
const auto& quoted = metrosync::testing_support::shellQuote;

std::string scratch(const std::string& name) {
  return metrosync::testing_support::scratchDir("cli", name);
}

// Runs `metrosync ARGS` in directory `cwd` (created if needed); captures stdout and stderr.
Result metrosync(const std::string& args, const std::string& cwd = ::testing::TempDir()) {
  return metrosync::testing_support::runMetrosync(args, {cwd, ""});
}

std::string writeFile(const std::string& path, const std::string& text) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path) << text;
  return path;
}

std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> v;
  std::string l;
  while (std::getline(in, l)) v.push_back(l);
  return v;
}

std::vector<double> numbers(const std::string& csv_line) {
  std::vector<double> v;
  std::stringstream ss(csv_line);
  std::string cell;
  while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
  return v;
}

json readJson(const std::string& path) {
  std::ifstream in(path);
  return json::parse(in);
}

std::set<std::string> listDir(const std::string& d) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(d)) names.insert(e.path().filename().string());
  return names;
}

// The SPEC 1b example with a short run; `extra` lines are appended at the top level.
std::string scaledRig(double tau, double mu = 0.4, const std::string& extra = "") {
  std::ostringstream os;
  os << "units: scaled\n"
        "name: cli-pair\n"
        "epsilon: 0.073\n"
        "platform:\n"
        "  friction: {law: coulomb, mu: "
     << mu
     << "}\n"
        "metronomes:\n"
        "  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: 1.9, phi: 0.03}}\n"
        "  - {nu: 0.7, J: 2.8, theta_c: 0.9, alpha: 0.0, start: {A: 1.9, phi: 0.0}}\n"
        "simulation:\n"
        "  tau: "
     << tau << "\n"
     << extra;
  return os.str();
}

const std::set<std::string> kRegimes = {"death",     "suppression",  "drift",     "in-phase",
                                        "antiphase", "phase-locked", "unsettled", "alive",
                                        "none",      "unknown"};

// ---------------------------------------------------------------------------------------------
// exit 2: bad rig, bad command line; nothing written

TEST(CliErrors, BadRigNamesFileLineAndKeyAndWritesNothing) {
  const std::string dir = scratch("badrig");
  // the typo "alpah" on line 8, in the second metronome
  std::string text = scaledRig(5);
  text.replace(text.find("alpha"), 5, "alpah");
  const std::string rig = writeFile(dir + "/in/typo.yaml", text);
  const Result r = metrosync("run " + quoted(rig) + " --out " + quoted(dir + "/out"), dir + "/cwd");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("metrosync: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("typo.yaml:8:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("alpah"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out"));
  // without --out, the default directory is not created either
  const Result d = metrosync("run " + quoted(rig), dir + "/cwd");
  EXPECT_EQ(d.code, 2);
  EXPECT_FALSE(fs::exists(dir + "/cwd/runs"));
  EXPECT_TRUE(r.out.empty());
}

TEST(CliErrors, BadValueFromSetNamesTheKeyAndValue) {
  const std::string dir = scratch("badset");
  const Result r = metrosync("run --set platform.friction.mu=-1 --out " + quoted(dir + "/out"));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("platform.friction.mu"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("-1"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out"));
}

TEST(CliErrors, MissingRigFile) {
  const std::string dir = scratch("missing");
  const Result r =
      metrosync("compare " + quoted(dir + "/nope.yaml") + " --out " + quoted(dir + "/out"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("nope.yaml"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out"));
}

TEST(CliErrors, UnknownIntegratorIsABadRig) {
  const std::string dir = scratch("integrator");
  for (const char* cmd : {"run", "compare"}) {
    const Result r =
        metrosync(std::string(cmd) + " --set simulation.integrator=no-such-integrator --out " +
                  quoted(dir + "/out"));
    EXPECT_EQ(r.code, 2) << cmd << ": " << r.err;
    EXPECT_NE(r.err.find("simulation.integrator"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("no-such-integrator"), std::string::npos) << r.err;
    // and says what would do
    EXPECT_NE(r.err.find(metrosync::simbodyIntegratorNames().front()), std::string::npos);
    EXPECT_FALSE(fs::exists(dir + "/out"));
  }
}

TEST(CliErrors, BadCommandLines) {
  const std::string cwd = scratch("cmdline");
  for (const char* args :
       {"", "frobnicate", "run --model medium", "run --no-such-option", "run --engine warp",
        "run a.yaml b.yaml", "scale --json --out x", "sweep"}) {
    const Result r = metrosync(args, cwd);
    EXPECT_EQ(r.code, 2) << "'" << args << "': " << r.err;
    EXPECT_EQ(r.err.rfind("metrosync: error: ", 0), 0u) << "'" << args << "': " << r.err;
  }
  EXPECT_FALSE(fs::exists(cwd + "/runs"));
}

TEST(CliHelp, ListsCommandsAndIntegrators) {
  const Result top = metrosync("--help");
  EXPECT_EQ(top.code, 0);
  for (const char* cmd : {"run", "compare", "scale"})
    EXPECT_NE(top.out.find(cmd), std::string::npos) << cmd;
  const Result run = metrosync("run --help");
  EXPECT_EQ(run.code, 0);
  for (const auto& name : metrosync::simbodyIntegratorNames())
    EXPECT_NE(run.out.find(name), std::string::npos) << name;
  for (const char* opt : {"--model", "--engine", "--out", "--set", "--quiet"})
    EXPECT_NE(run.out.find(opt), std::string::npos) << opt;
  for (const char* cmd : {"compare --help", "scale --help"}) EXPECT_EQ(metrosync(cmd).code, 0);
}

// ---------------------------------------------------------------------------------------------
// scale --json: exactly one JSON object with the SPEC keys

TEST(CliScale, JsonIsOneObjectWithTheSpecKeys) {
  const std::string dir = scratch("scale");
  const std::string rig = writeFile(dir + "/pair.yaml", scaledRig(10, 0.4));
  const Result r = metrosync("scale --json " + quoted(rig));
  ASSERT_EQ(r.code, 0) << r.err;
  json j;
  ASSERT_NO_THROW(j = json::parse(r.out)) << r.out;  // the whole of stdout: one value
  ASSERT_TRUE(j.is_object());
  for (const char* key : {"epsilon", "mu", "time_scale"}) EXPECT_TRUE(j.contains(key)) << key;
  for (const char* key : {"nu", "J", "theta_c", "alpha", "zeta", "A_star"}) {
    ASSERT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j[key].size(), 2u) << key;
  }
  // a scaled rig reports what it was given
  EXPECT_NEAR(j["epsilon"].get<double>(), 0.073, 1e-12);
  EXPECT_NEAR(j["mu"].get<double>(), 0.4, 1e-12);
  EXPECT_NEAR(j["nu"][1].get<double>(), 0.7, 1e-12);
  EXPECT_NEAR(j["J"][0].get<double>(), 2.8, 1e-12);
  EXPECT_NEAR(j["theta_c"][1].get<double>(), 0.9, 1e-12);
  // --set reaches it, and a viscous platform reports c instead of mu
  const Result v = metrosync("scale " + quoted(rig) +
                             " --json --set 'platform.friction={law: viscous, c: 0.3}'");
  ASSERT_EQ(v.code, 0) << v.err;
  const json jv = json::parse(v.out);
  EXPECT_NEAR(jv["c"].get<double>(), 0.3, 1e-12);
  // the default rig, and the table form
  EXPECT_NO_THROW(json::parse(metrosync("scale --json").out));
  const Result text = metrosync("scale " + quoted(rig));
  EXPECT_EQ(text.code, 0);
  EXPECT_NE(text.out.find("epsilon"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// run: the SPEC 3 files

void expectNoTemporaryFiles(const std::string& dir) {
  for (const auto& name : listDir(dir)) EXPECT_NE(name[0], '.') << "left behind: " << name;
}

void expectEnvelope(const std::string& path, int n, double tau_end) {
  const auto l = lines(path);
  ASSERT_GE(l.size(), 2u) << path;
  // SPEC's columns; a physical rig's file appends t_s (seconds, docs/outputs.md)
  EXPECT_TRUE(l[0] == metrosync::envelopeHeader(n) || l[0] == metrosync::envelopeHeader(n) + ",t_s")
      << l[0];
  const auto rows = metrosync::readEnvelopeCsv(path);
  double prev = -1;
  for (const auto& r : rows) {
    EXPECT_GT(r.tau, prev);
    EXPECT_LE(r.tau, tau_end * (1 + 1e-9));
    prev = r.tau;
  }
}

// A summary.json (or, with top_level = false, one model's part of compare's).
void expectSummary(const json& s, const std::string& model, int n, bool top_level = true) {
  for (const char* key : {"model", "regime", "final", "counts", "wall_seconds", "complete",
                          "engine", "integrator", "accuracy"})
    EXPECT_TRUE(s.contains(key)) << key;
  if (top_level) {
    for (const char* key : {"units", "scaled", "rig", "version"})
      EXPECT_TRUE(s.contains(key)) << key;
  }
  EXPECT_EQ(s["model"], model);
  EXPECT_TRUE(s["complete"].get<bool>()) << s.dump(2);
  EXPECT_FALSE(s.contains("failure"));
  // N >= 3: the clusters' names of sim/analysis/regime.h (in-phase, clusters:3+2,
  // suppressed:1;drift, ...)
  const std::regex many(
      "(suppressed:[0-9]+;?)?(in-phase|phase-locked|drift|unsettled|"
      "clusters:[0-9x+]+)?");
  const std::string regime = s["regime"].get<std::string>();
  EXPECT_TRUE(kRegimes.count(regime) ||
              (n >= 3 && !regime.empty() && std::regex_match(regime, many)))
      << regime;
  EXPECT_EQ(s["final"]["A"].size(), static_cast<size_t>(n));
  EXPECT_EQ(s["final"]["psi"].size(), static_cast<size_t>(n - 1));
  for (const char* key : {"steps", "escapements", "stick_slip"})
    EXPECT_TRUE(s["counts"].contains(key)) << key;
}

TEST(CliRun, FullModelWritesEveryFile) {
  const std::string dir = scratch("runfull");
  const Result r = metrosync("run --set simulation.duration=5 --out " + quoted(dir));
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"trajectory.csv", "envelope.csv", "summary.json"})
    EXPECT_TRUE(fs::exists(dir + "/" + f)) << f;
  expectNoTemporaryFiles(dir);

  // trajectory: header, the start as the first row, the end as the last
  const auto traj = lines(dir + "/trajectory.csv");
  ASSERT_GE(traj.size(), 3u);
  EXPECT_EQ(traj[0], "t,x,xdot,theta_1,thetadot_1,theta_2,thetadot_2,platform");
  const auto first = numbers(traj[1]), last = numbers(traj.back());
  ASSERT_EQ(first.size(), 8u);
  ASSERT_EQ(last.size(), 8u);
  EXPECT_EQ(first[0], 0.0);
  // the default rig starts at angles +-0.785 rad, metronome B at 0.25 rad/s (yaml/rigs)
  EXPECT_NEAR(first[3], 0.785, 1e-9);
  EXPECT_NEAR(first[5], -0.785, 1e-9);
  EXPECT_NEAR(first[6], 0.25, 1e-9);
  EXPECT_NEAR(last[0], 5.0, 1e-6);
  for (size_t k = 1; k < traj.size(); ++k) {
    const auto row = numbers(traj[k]);
    ASSERT_EQ(row.size(), 8u) << "line " << k + 1;
    EXPECT_TRUE(row[7] == 0 || row[7] == 1 || row[7] == -1) << "line " << k + 1;
  }

  const json s = readJson(dir + "/summary.json");
  expectSummary(s, "full", 2);
  EXPECT_EQ(s["units"], "physical");
  EXPECT_EQ(s["counts"]["escapements"].size(), 2u);
  EXPECT_GT(s["counts"]["escapements"][0].get<long>(), 0);  // 5 s of ticking
  const double tau_end = s["final"]["tau"].get<double>();
  expectEnvelope(dir + "/envelope.csv", 2, tau_end);
  // the summary's final row is the envelope's last
  const auto env = metrosync::readEnvelopeCsv(dir + "/envelope.csv");
  ASSERT_FALSE(env.empty());
  EXPECT_NEAR(env.back().A[0], s["final"]["A"][0].get<double>(), 1e-9);
  // summary.scaled is what `scale --json` prints for the same rig
  const json scaled = json::parse(metrosync("scale --json --set simulation.duration=5").out);
  EXPECT_EQ(s["scaled"], scaled);
  // a human summary on stdout, nothing with --quiet
  EXPECT_NE(r.out.find(s["regime"].get<std::string>()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(dir), std::string::npos) << r.out;
  const Result q = metrosync("run --quiet --set simulation.duration=1 --out " + quoted(dir));
  EXPECT_EQ(q.code, 0);
  EXPECT_TRUE(q.out.empty()) << q.out;
}

TEST(CliRun, SlowFlowWritesNoTrajectoryAndReplacesAnOlderRun) {
  const std::string dir = scratch("runslow");
  ASSERT_EQ(metrosync("run --quiet --set simulation.duration=2 --out " + quoted(dir)).code, 0);
  ASSERT_TRUE(fs::exists(dir + "/trajectory.csv"));
  const Result r = metrosync("run --model slow --set simulation.duration=20 --out " + quoted(dir));
  ASSERT_EQ(r.code, 0) << r.err;
  // the full run's trajectory is gone: every file in DIR belongs to this run
  EXPECT_FALSE(fs::exists(dir + "/trajectory.csv"));
  const json s = readJson(dir + "/summary.json");
  expectSummary(s, "slow", 2);
  expectEnvelope(dir + "/envelope.csv", 2, s["final"]["tau"].get<double>());
  // 20 s is tau_end = eps t / time_scale; the last row is within one fast period of it
  const json& sc = s["scaled"];
  const double tau_end = sc["epsilon"].get<double>() * 20.0 / sc["time_scale"].get<double>();
  const double period = metrosync::kTwoPi * sc["epsilon"].get<double>();
  EXPECT_NEAR(s["final"]["tau"].get<double>(), tau_end, period);
  expectNoTemporaryFiles(dir);
}

// --no-plot: the same files without the PNG (and without the gnuplot child). The default run's
// PNG is checked too, so that the test fails if plotting were off anyway; it needs gnuplot.
TEST(CliRun, NoPlotWritesNoPng) {
  ASSERT_EQ(std::system("command -v gnuplot > /dev/null 2>&1"), 0)
      << "gnuplot not on PATH (tools/setup.sh installs gnuplot-nox): no run could write a PNG";
  const std::string dir = scratch("noplot");
  ASSERT_EQ(
      metrosync("run --quiet --set simulation.duration=2 --out " + quoted(dir + "/plot")).code, 0);
  EXPECT_TRUE(fs::exists(dir + "/plot/envelope.png"));
  for (const char* cmd : {"run", "compare"}) {
    const std::string out = dir + "/" + cmd;
    const Result r = metrosync(
        std::string(cmd) + " --quiet --no-plot --set simulation.duration=2 --out " + quoted(out));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(out + "/summary.json")) << cmd;
    for (const auto& name : listDir(out))
      EXPECT_NE(fs::path(name).extension(), ".png") << cmd << " wrote " << name;
    const json s = readJson(out + "/summary.json");
    for (const auto& f : s["files"])
      EXPECT_EQ(f.get<std::string>().find(".png"), std::string::npos) << f;
  }
}

// Every metronome locked (section 3A, yaml/rigs/board-on-springs.yaml): the summary on stdout
// reports the board's linear decay that summary.json's section3a holds, not amplitudes and
// thresholds that locked pendulums do not have ("A = 0 0 (theta_c = 0 0)").
TEST(CliRun, LockedMetronomesSummarizeTheBoardsDecay) {
  const std::string dir = scratch("locked");
  const Result r = metrosync(
      "run " + quoted(std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/board-on-springs.yaml") +
      " --no-plot --out " + quoted(dir));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.find("theta_c = 0"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("A = 0 0"), std::string::npos) << r.out;
  const json s = readJson(dir + "/summary.json")["section3a"];
  char mu_bar[32], slope[32];
  std::snprintf(mu_bar, sizeof mu_bar, "mu-bar %.4g", s["mu_bar"].get<double>());
  std::snprintf(slope, sizeof slope, "slope %.4g m/s", s["slope"].get<double>());
  EXPECT_NE(r.out.find("every metronome locked"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(mu_bar), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(slope), std::string::npos) << r.out;
}

TEST(CliRun, ScaledRigThreeMetronomes) {
  const std::string dir = scratch("three");
  std::string text = scaledRig(8, 0.2);
  text.insert(text.find("simulation:"),
              "  - {nu: 0.7, J: 2.8, theta_c: 0.9, alpha: 0.1, start: {A: 1.5, phi: 3.0}}\n");
  const std::string rig = writeFile(dir + "/three.yaml", text);
  const Result r = metrosync("run " + quoted(rig) + " --out " + quoted(dir + "/out"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(lines(dir + "/out/trajectory.csv")[0],
            "t,x,xdot,theta_1,thetadot_1,theta_2,thetadot_2,theta_3,thetadot_3,platform");
  const json s = readJson(dir + "/out/summary.json");
  expectSummary(s, "full", 3);
  EXPECT_EQ(s["units"], "scaled");
  EXPECT_EQ(s["rig"], "cli-pair");
  expectEnvelope(dir + "/out/envelope.csv", 3, 8.0);
}

// ---------------------------------------------------------------------------------------------
// compare

TEST(CliCompare, WritesComparisonAndBothEnvelopes) {
  const std::string dir = scratch("compare");
  const std::string rig = writeFile(dir + "/pair.yaml", scaledRig(6));
  const Result r = metrosync("compare " + quoted(rig) + " --out " + quoted(dir + "/out"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string out = dir + "/out";
  for (const char* f : {"trajectory.csv", "envelope_full.csv", "envelope_slow.csv",
                        "comparison.csv", "summary.json"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  expectNoTemporaryFiles(out);
  const auto cmp = lines(out + "/comparison.csv");
  ASSERT_GE(cmp.size(), 2u);
  EXPECT_EQ(cmp[0], "tau,A_1_full,A_1_slow,A_2_full,A_2_slow,psi_2_full,psi_2_slow");
  const auto full = metrosync::readEnvelopeCsv(out + "/envelope_full.csv");
  const auto slow = metrosync::readEnvelopeCsv(out + "/envelope_slow.csv");
  // one line per grid tau both models reached (rows sit on the grid tau_k = 2 pi eps (k + 1/2));
  // each file's first row (the start, tau = 0) and last row (the final state at tau_end) are off
  // the grid and not compared (docs/outputs.md)
  ASSERT_GE(full.size(), 3u);
  ASSERT_GE(slow.size(), 3u);
  EXPECT_EQ(full.front().tau, 0.0);
  EXPECT_EQ(slow.front().tau, 0.0);
  EXPECT_EQ(full.back().tau, slow.back().tau);
  std::set<long> full_k, common;
  for (size_t k = 1; k + 1 < full.size(); ++k)
    full_k.insert(std::lround(full[k].tau / (metrosync::kTwoPi * 0.073) - 0.5));
  for (size_t k = 1; k + 1 < slow.size(); ++k)
    if (full_k.count(std::lround(slow[k].tau / (metrosync::kTwoPi * 0.073) - 0.5)))
      common.insert(std::lround(slow[k].tau / (metrosync::kTwoPi * 0.073) - 0.5));
  EXPECT_GT(common.size(), 10u);
  EXPECT_EQ(cmp.size() - 1, common.size());
  // each line pairs the two models' rows at the same tau
  const auto v = numbers(cmp[1]);
  ASSERT_EQ(v.size(), 7u);
  EXPECT_NEAR(v[0], full[1].tau, 1e-9);
  EXPECT_NEAR(v[0], slow[1].tau, 1e-9);
  EXPECT_NEAR(v[1], full[1].A[0], 1e-9);
  EXPECT_NEAR(v[2], slow[1].A[0], 1e-9);

  const json s = readJson(out + "/summary.json");
  EXPECT_TRUE(s["complete"].get<bool>());
  ASSERT_TRUE(s.contains("comparison"));
  ASSERT_EQ(s["comparison"]["max_abs_dA"].size(), 2u);
  ASSERT_EQ(s["comparison"]["max_abs_dpsi"].size(), 1u);
  // the maxima are those of the file
  double max_dA1 = 0;
  for (size_t k = 1; k < cmp.size(); ++k) {
    const auto row = numbers(cmp[k]);
    max_dA1 = std::max(max_dA1, std::fabs(row[1] - row[2]));
  }
  EXPECT_NEAR(s["comparison"]["max_abs_dA"][0].get<double>(), max_dA1, 1e-9);
  expectSummary(s["models"]["full"], "full", 2, false);
  expectSummary(s["models"]["slow"], "slow", 2, false);
  EXPECT_EQ(s["regime"], s["models"]["full"]["regime"]);
  EXPECT_TRUE(kRegimes.count(s["regime"].get<std::string>()));
}

// ---------------------------------------------------------------------------------------------
// interrupted runs: files whole or not at all

// Starts a long run in the background, waits until it is writing, sends `signal`; returns the
// exit code (128 + signal when killed).
int interruptLongRun(const std::string& dir, const std::string& command, int signal) {
  const std::string rig = writeFile(dir + "/long.yaml", scaledRig(20000, 0.2));
  const std::string out = dir + "/out";
  const std::string script =
      quoted(METROSYNC_BINARY) + " " + command + " " + quoted(rig) + " --quiet --out " +
      quoted(out) + " 2>/dev/null & pid=$!; " +
      // wait (at most 30 s) until the run writes its files, then let it write for a moment
      "for i in $(seq 600); do ls -A " + quoted(out) +
      " 2>/dev/null | grep -q part && break; sleep 0.05; done; sleep 0.5; kill -" +
      std::to_string(signal) + " $pid; wait $pid; echo $? > " + quoted(dir + "/code");
  std::system(("bash -c " + quoted(script)).c_str());
  return std::stoi(slurp(dir + "/code"));
}

TEST(CliInterrupted, SigintKeepsTheRowsAndSaysIncomplete) {
  const std::string dir = scratch("sigint");
  EXPECT_EQ(interruptLongRun(dir, "run", SIGINT), 3);
  const std::string out = dir + "/out";
  expectNoTemporaryFiles(out);
  const json s = readJson(out + "/summary.json");
  EXPECT_FALSE(s["complete"].get<bool>());
  EXPECT_NE(s["failure"].get<std::string>().find("interrupted"), std::string::npos);
  EXPECT_EQ(s["regime"], "unknown");
  const auto traj = lines(out + "/trajectory.csv");
  ASSERT_GE(traj.size(), 3u);
  for (size_t k = 1; k < traj.size(); ++k) ASSERT_EQ(numbers(traj[k]).size(), 8u);
  EXPECT_GE(metrosync::readEnvelopeCsv(out + "/envelope.csv").size(), 1u);
}

TEST(CliInterrupted, KilledRunLeavesNoFileThatLooksComplete) {
  const std::string dir = scratch("sigkill");
  EXPECT_EQ(interruptLongRun(dir, "run", SIGKILL), 128 + SIGKILL);
  for (const auto& name : listDir(dir + "/out")) {
    EXPECT_EQ(name[0], '.') << name;
    EXPECT_NE(name.find(".part"), std::string::npos) << name;
  }
  // the next run in the same directory clears what the killed one left
  ASSERT_EQ(metrosync("run --model slow --quiet --set simulation.duration=1 --out " +
                      quoted(dir + "/out"))
                .code,
            0);
  expectNoTemporaryFiles(dir + "/out");
}

}  // namespace
