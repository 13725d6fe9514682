// Reproducible outputs (issue 16): summary.json's resolved rig runs as is and reproduces the run
// bit for bit, the build keys name the commit git names, the default folder depends on the
// overrides, events.csv agrees with the counts and conserves momentum at mu = 0, and physical
// rigs carry seconds in every CSV.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "models/rig.h"
#include "sim/record/atomic_file.h"
#include "tests/common/run_metrosync.h"
#include "tools/report/outputs.h"
#include "yaml/rig_loader.h"

namespace {

namespace fs = std::filesystem;
using metrosync::testing_support::CommandResult;
using metrosync::testing_support::runMetrosync;
using metrosync::testing_support::slurp;
using nlohmann::json;
const auto& quoted = metrosync::testing_support::shellQuote;

std::string scratch(const std::string& name) {
  return metrosync::testing_support::scratchDir("repro", name, true);
}

CommandResult metrosync(const std::string& args, const std::string& cwd) {
  return runMetrosync(args, {cwd, ""});
}

json readJson(const std::string& path) {
  std::ifstream in(path);
  return json::parse(in);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> v;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) v.push_back(cell);
  return v;
}

// A CSV as a header and rows of cells.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  int column(const std::string& name) const {
    for (size_t k = 0; k < header.size(); ++k)
      if (header[k] == name) return static_cast<int>(k);
    return -1;
  }
  double number(size_t row, const std::string& name) const {
    return std::stod(rows.at(row).at(column(name)));
  }
};

Csv readCsv(const std::string& path) {
  std::ifstream in(path);
  Csv c;
  std::string line;
  if (std::getline(in, line)) c.header = split(line);
  while (std::getline(in, line))
    if (!line.empty()) c.rows.push_back(split(line));
  return c;
}

const char* kScaledRig =
    "units: scaled\n"
    "epsilon: 0.073\n"
    "platform:\n"
    "  friction: {law: coulomb, mu: 0.4}\n"
    "metronomes:\n"
    "  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: 1.9, phi: 0.03}}\n"
    "  - {nu: 0.7, J: 2.8, theta_c: 0.9, alpha: 0.02, start: {A: 1.9, phi: 3.0}}\n"
    "simulation:\n"
    "  tau: 3\n";

// Runs `args` into dir/a, writes its summary's resolved_rig to dir/resolved.yaml, runs that with
// `rerun_args` into dir/b, and expects every CSV of the two runs to be the same bytes.
void expectRoundTrip(const std::string& dir, const std::string& args,
                     const std::string& rerun_args) {
  const CommandResult a = metrosync(args + " --no-plot -q --out a", dir);
  ASSERT_EQ(a.code, 0) << a.err;
  const json sa = readJson(dir + "/a/summary.json");
  ASSERT_TRUE(sa.contains("resolved_rig"));
  std::ofstream(dir + "/resolved.yaml") << sa["resolved_rig"].dump(2) << "\n";
  const CommandResult b =
      metrosync("run resolved.yaml " + rerun_args + " --no-plot -q --out b", dir);
  ASSERT_EQ(b.code, 0) << b.err;
  const json sb = readJson(dir + "/b/summary.json");
  EXPECT_EQ(sa["resolved_rig"], sb["resolved_rig"]) << "the resolved rig is not a fixed point";
  int compared = 0;
  for (const auto& f : sa["files"]) {
    const std::string name = f.get<std::string>();
    if (fs::path(name).extension() != ".csv") continue;
    ++compared;
    const std::string ta = slurp(dir + "/a/" + name), tb = slurp(dir + "/b/" + name);
    EXPECT_FALSE(ta.empty()) << name;
    EXPECT_TRUE(ta == tb) << name << " differs between the run and its resolved rig's run";
  }
  EXPECT_GE(compared, 1);
  for (const char* key : {"final", "counts", "network"})  // a network's summary has no final
    if (sa.contains(key)) {
      EXPECT_EQ(sa[key], sb[key]) << key;
    }
}

TEST(SummaryRoundTrip, DirectEngineWithOverrides) {
  const std::string dir = scratch("direct");
  expectRoundTrip(dir,
                  "run --engine direct --set simulation.duration=3 "
                  "--set platform.friction.mu=0.002 --set metronomes.1.start.angle=-0.6",
                  "--engine direct");
  // the overrides are in the tree, not only in the command line
  const json s = readJson(dir + "/a/summary.json");
  EXPECT_EQ(s["resolved_rig"]["platform"]["friction"]["mu"], 0.002);
  EXPECT_EQ(s["resolved_rig"]["metronomes"][1]["start"]["angle"], -0.6);
  EXPECT_EQ(s["resolved_rig"]["name"], "experiment");
}

TEST(SummaryRoundTrip, SimbodyEngine) {
  expectRoundTrip(scratch("simbody"),
                  "run --engine simbody --set simulation.duration=0.6 "
                  "--set platform.friction.mu=0.002",
                  "--engine simbody");
}

TEST(SummaryRoundTrip, ScaledRigWithoutNameBothModels) {
  const std::string dir = scratch("scaled");
  std::ofstream(dir + "/pair.yaml") << kScaledRig;
  expectRoundTrip(dir, "run pair.yaml --engine direct --set platform.friction.mu=0.3",
                  "--engine direct");
  const json s = readJson(dir + "/a/summary.json");
  EXPECT_EQ(s["resolved_rig"]["name"], "pair");  // the file's stem, now written down
  EXPECT_EQ(s["resolved_rig"]["platform"]["friction"]["mu"], 0.3);
  fs::remove_all(dir + "/a");
  fs::remove_all(dir + "/b");
  expectRoundTrip(dir, "run pair.yaml --model slow --set metronomes.0.J=3.1", "--model slow");
}

TEST(SummaryRoundTrip, NetworkOfPlatforms) {
  const std::string dir = scratch("network");
  const std::string rig = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/two-boards-rollers.yaml";
  expectRoundTrip(
      dir,
      "run " + quoted(rig) + " --engine direct --set simulation.duration=3 --set couplings.0.k=3.5",
      "--engine direct");
  const json s = readJson(dir + "/a/summary.json");
  EXPECT_EQ(s["resolved_rig"]["couplings"][0]["k"], 3.5);
}

TEST(SummaryProvenance, CommandLineBuildAndEngine) {
  const std::string dir = scratch("provenance");
  const std::string args =
      "run --engine direct --set simulation.duration=1 --set simulation.accuracy=1e-9";
  const CommandResult r = metrosync(args + " --no-plot -q --out o", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const json s = readJson(dir + "/o/summary.json");
  std::vector<std::string> want = {METROSYNC_BINARY};
  std::stringstream ss(args + " --no-plot -q --out o");
  for (std::string w; ss >> w;) want.push_back(w);
  EXPECT_EQ(s["command_line"].get<std::vector<std::string>>(), want);
  EXPECT_EQ(s["engine"], "direct");
  EXPECT_EQ(s["accuracy"], 1e-9);
  EXPECT_FALSE(s["integrator"].get<std::string>().empty());
  EXPECT_EQ(s["version"], s["build"]["metrosync"]);  // the existing key is kept as it was
  for (const char* key : {"commit", "simbody", "eigen"})
    EXPECT_FALSE(s["build"][key].get<std::string>().empty()) << key;
}

std::string gitHead(const std::string& source) {
  // the source folder's own commit, if it is the top of a git work tree (else "unknown")
  const std::string q = quoted(source);
  const std::string cmd = "cd " + q +
                          " && [ \"$(git rev-parse --show-toplevel 2>/dev/null)\" = "
                          "\"$(pwd -P)\" ] && git rev-parse HEAD 2>/dev/null";
  FILE* p = ::popen(cmd.c_str(), "r");
  std::string out;
  char buf[128];
  while (p && std::fgets(buf, sizeof buf, p)) out += buf;
  if (p) ::pclose(p);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out.empty() ? "unknown" : out;
}

TEST(Version, PrintsTheCommitGitNames) {
  const CommandResult r = runMetrosync("--version");
  ASSERT_EQ(r.code, 0) << r.err;
  std::stringstream ss(r.out);
  std::string version, commit_line;
  std::getline(ss, version);
  std::getline(ss, commit_line);
  EXPECT_EQ(version, metrosync::metrosyncVersion());  // first line: the version alone (man page)
  ASSERT_EQ(commit_line.rfind("commit ", 0), 0u) << r.out;
  std::string commit = commit_line.substr(7);
  const std::string head = gitHead(fs::canonical(METROSYNC_SOURCE_DIR).string());
  // the build may be older than HEAD only if it was not rebuilt: the test binary was built with it
  const std::string base = commit.substr(0, commit.find("-dirty"));
  EXPECT_EQ(base, head) << "--version says " << commit;
  if (head == "unknown") {
    EXPECT_EQ(commit, "unknown");
  }
  EXPECT_NE(r.out.find("Simbody "), std::string::npos);
  EXPECT_NE(r.out.find("Eigen "), std::string::npos);

  // summary.json says the same
  const std::string dir = scratch("version");
  ASSERT_EQ(
      metrosync("run --set simulation.duration=0.5 --engine direct --no-plot -q --out o", dir).code,
      0);
  EXPECT_EQ(readJson(dir + "/o/summary.json")["build"]["commit"], commit);
}

// FNV-1a 64 ("a") = 0xaf63dc4c8601ec8c is the algorithm's published test vector; the folder
// suffixes below are the top 32 bits of FNV-1a over "KEY=VALUE\n" per override, computed apart.
TEST(DefaultFolder, OverridesGetTheirOwnFolder) {
  EXPECT_EQ(metrosync::overridesHash({}), 0xcbf29ce484222325ull);  // the offset basis
  EXPECT_EQ(metrosync::defaultOutputDir("experiment", "run"), "runs/experiment-run");
  EXPECT_EQ(metrosync::defaultOutputDir("experiment", "run", {"platform.friction.mu=0.3"}),
            "runs/experiment-run-791f64d7");
  EXPECT_EQ(metrosync::defaultOutputDir("experiment", "run",
                                        {"simulation.duration=2", "platform.friction.mu=0.002"}),
            "runs/experiment-run-1b530295");

  const std::string dir = scratch("folders");
  const std::string base = "run --engine direct --no-plot -q --set simulation.duration=0.5";
  ASSERT_EQ(metrosync("run --engine direct --no-plot -q", dir + "/plain").code, 0);
  EXPECT_TRUE(fs::exists(dir + "/plain/runs/experiment-run/summary.json"));
  ASSERT_EQ(metrosync(base + " --set platform.friction.mu=0.001", dir).code, 0);
  ASSERT_EQ(metrosync(base + " --set platform.friction.mu=0.003", dir).code, 0);
  std::vector<std::string> folders;
  for (const auto& e : fs::directory_iterator(dir + "/runs"))
    folders.push_back(e.path().filename().string());
  ASSERT_EQ(folders.size(), 2u) << "two configurations, two folders";
  for (const auto& f : folders) {
    const json s = readJson(dir + "/runs/" + f + "/summary.json");
    const double mu = s["resolved_rig"]["platform"]["friction"]["mu"];
    const std::vector<std::string> sets = {
        "simulation.duration=0.5",
        std::string("platform.friction.mu=") + (mu < 0.002 ? "0.001" : "0.003")};
    EXPECT_EQ("runs/" + f, metrosync::defaultOutputDir("experiment", "run", sets));
  }
  // the same overrides again: the same folder (stable), replaced
  ASSERT_EQ(metrosync(base + " --set platform.friction.mu=0.001", dir).code, 0);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir + "/runs"), fs::directory_iterator{}), 2);
}

// P = M xdot + sum m_i L_i cos(theta_i) thetadot_i (SI) from an events.csv row's columns
double momentum(const metrosync::Rig& rig, const Csv& c, size_t row, const std::string& when) {
  double p = rig.totalMass() * c.number(row, "xdot" + when);
  for (size_t i = 0; i < rig.metronomes.size(); ++i) {
    const auto& m = rig.metronomes[i];
    const std::string k = std::to_string(i + 1);
    p += m.pendulum_mass_kg * m.length_m * std::cos(c.number(row, "theta_" + k + when)) *
         c.number(row, "thetadot_" + k + when);
  }
  return p;
}

void expectEventsMatchCounts(const std::string& dir, const std::string& engine) {
  const Csv ev = readCsv(dir + "/events.csv");
  const json s = readJson(dir + "/summary.json");
  ASSERT_EQ(ev.column("t"), 0);
  ASSERT_GE(ev.column("platform_after"), 0);
  const size_t n = s["counts"]["escapements"].size();
  std::vector<long> ticks(n, 0);
  long switches = 0, at_start = 0;
  for (size_t r = 0; r < ev.rows.size(); ++r) {
    const std::string kind = ev.rows[r][ev.column("kind")], who = ev.rows[r][ev.column("who")];
    if (kind == "tick") {
      ++ticks.at(std::stoul(who) - 1);
    } else {
      EXPECT_EQ(who, "platform");
      (ev.number(r, "t") > 0 ? switches : at_start) += 1;
    }
  }
  for (size_t i = 0; i < n; ++i)
    EXPECT_EQ(ticks[i], s["counts"]["escapements"][i].get<long>()) << engine << " metronome " << i;
  EXPECT_EQ(switches,
            s["counts"]["stick_slip"].get<long>() + s["counts"]["slip_reversals"].get<long>())
      << engine;
  EXPECT_LE(at_start, 1);
}

TEST(EventsCsv, RowsMatchTheCountsAndTicksConserveMomentumAtMuZero) {
  const std::string dir = scratch("events");
  for (const std::string engine : {"direct", "simbody"}) {
    const std::vector<std::string> sets = {"platform.friction.mu=0", engine == "direct"
                                                                         ? "simulation.duration=4"
                                                                         : "simulation.duration=1"};
    const CommandResult r = metrosync("run --engine " + engine + " --no-plot -q --out " + engine +
                                          " --set " + sets[0] + " --set " + sets[1],
                                      dir);
    ASSERT_EQ(r.code, 0) << r.err;
    expectEventsMatchCounts(dir + "/" + engine, engine);
    const metrosync::Rig rig = metrosync::defaultRig(sets);
    const Csv ev = readCsv(dir + "/" + engine + "/events.csv");
    const auto& m0 = rig.metronomes[0];
    const double scale = m0.pendulum_mass_kg * m0.length_m * 10.0;  // |thetadot| ~ 10 rad/s
    long ticks = 0;
    for (size_t row = 0; row < ev.rows.size(); ++row) {
      if (ev.rows[row][ev.column("kind")] != "tick") continue;
      ++ticks;
      const std::string k = ev.rows[row][ev.column("who")];
      // the jump: the ticking pendulum's velocity changes, the platform takes the reaction
      EXPECT_NE(ev.number(row, "thetadot_" + k + "_before"),
                ev.number(row, "thetadot_" + k + "_after"));
      EXPECT_NE(ev.number(row, "xdot_before"), ev.number(row, "xdot_after"));
      EXPECT_EQ(ev.number(row, "theta_" + k + "_before"), ev.number(row, "theta_" + k + "_after"));
      EXPECT_NEAR(momentum(rig, ev, row, "_before"), momentum(rig, ev, row, "_after"), 1e-9 * scale)
          << engine << " row " << row + 2;
    }
    EXPECT_GE(ticks, 4) << engine;
  }
}

TEST(EventsCsv, StickSlipRowsMatchTheCountsWithFriction) {
  const std::string dir = scratch("events_mu");
  const CommandResult r = metrosync(
      "run --engine direct --no-plot -q --out o --set simulation.duration=3 "
      "--set platform.friction.mu=0.002",
      dir);
  ASSERT_EQ(r.code, 0) << r.err;
  expectEventsMatchCounts(dir + "/o", "direct");
  const json s = readJson(dir + "/o/summary.json");
  EXPECT_GT(s["counts"]["stick_slip"].get<long>(), 2);  // the case has switches to count
  // a stick row ends with the platform at rest, stuck
  const Csv ev = readCsv(dir + "/o/events.csv");
  for (size_t row = 0; row < ev.rows.size(); ++row)
    if (ev.rows[row][ev.column("kind")] == "stick") {
      EXPECT_EQ(ev.number(row, "xdot_after"), 0.0);
      EXPECT_EQ(ev.number(row, "platform_after"), 0.0);
    }
}

TEST(Seconds, PhysicalRigsGetTSInEveryCsvScaledRigsDoNot) {
  const std::string dir = scratch("seconds");
  ASSERT_EQ(metrosync("compare --set simulation.duration=4 --no-plot -q --out c", dir).code, 0);
  const CommandResult sc = metrosync("scale --json", dir);
  ASSERT_EQ(sc.code, 0);
  const json scaled = json::parse(sc.out);
  const double per_tau =
      scaled["time_scale"].get<double>() / scaled["epsilon"].get<double>();  // seconds per tau
  for (const char* f : {"envelope_full.csv", "envelope_slow.csv", "comparison.csv"}) {
    const Csv c = readCsv(dir + "/c/" + f);
    ASSERT_EQ(c.header.back(), "t_s") << f;
    ASSERT_EQ(c.header.front(), "tau") << f;
    ASSERT_GE(c.rows.size(), 3u) << f;
    for (size_t row = 0; row < c.rows.size(); ++row)
      EXPECT_NEAR(c.number(row, "t_s"), c.number(row, "tau") * per_tau,
                  1e-9 * (1 + c.number(row, "t_s")))
          << f << " row " << row + 2;
  }
  for (const char* f : {"envelope_full.csv", "envelope_slow.csv"}) {
    const Csv c = readCsv(dir + "/c/" + f);
    EXPECT_EQ(c.number(0, "tau"), 0.0) << f << " begins at tau = 0";
    EXPECT_NEAR(c.number(c.rows.size() - 1, "t_s"), 4.0, 1e-6) << f << " ends at the duration";
  }
  const Csv ev = readCsv(dir + "/c/events.csv");
  ASSERT_EQ(ev.header.back(), "t_s");
  ASSERT_GE(ev.rows.size(), 3u);
  for (size_t row = 0; row < ev.rows.size(); ++row) {
    EXPECT_EQ(ev.number(row, "t_s"), ev.number(row, "t"));  // t: the rig's unit, seconds here
    EXPECT_NEAR(ev.number(row, "t_s"), ev.number(row, "tau") * per_tau,
                1e-9 * (1 + ev.number(row, "t_s")));
  }
  // trajectory.csv keeps SPEC's columns: its t is in seconds already for a physical rig
  const Csv traj = readCsv(dir + "/c/trajectory.csv");
  EXPECT_EQ(traj.column("t_s"), -1);
  EXPECT_NEAR(traj.number(traj.rows.size() - 1, "t"), 4.0, 1e-9);
  // the existing columns are untouched: the envelope header is SPEC's, then t_s
  const Csv env = readCsv(dir + "/c/envelope_full.csv");
  std::vector<std::string> core(env.header.begin(), env.header.end() - 1);
  EXPECT_EQ(core, split(metrosync::envelopeHeader(2)));

  std::ofstream(dir + "/pair.yaml") << kScaledRig;
  ASSERT_EQ(metrosync("compare pair.yaml --no-plot -q --out s", dir).code, 0);
  for (const char* f :
       {"envelope_full.csv", "envelope_slow.csv", "comparison.csv", "trajectory.csv", "events.csv"})
    EXPECT_EQ(readCsv(dir + "/s/" + f).column("t_s"), -1) << f;
  EXPECT_EQ(readCsv(dir + "/s/envelope_full.csv").number(0, "tau"), 0.0);
}

}  // namespace
