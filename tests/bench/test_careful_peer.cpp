// The careful peer as a method of the bench (tools/bench/careful_peer.h, peer_scene.h): a scene
// becomes the peer's arguments (the scaled parameters `metrosync scale --json` prints, the start
// in scaled units), the peer's answer the bench's final state, and the subprocess plumbing works
// with a stand-in peer (a script that prints a JSON line). No test needs the real peer (CI has no
// shared/); one cross-check runs only where the peer is found. Also `runcost` and `maps` end to
// end on stand-ins or a tiny scene. No timing is checked.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "base/csv.h"
#include "contact/law_registry.h"
#include "tests/bench/bench_rig.h"
#include "tests/common/run_metrosync.h"
#include "tools/bench/bench_run.h"
#include "tools/bench/careful_peer.h"
#include "tools/bench/map_timing.h"
#include "tools/bench/peer_scene.h"
#include "tools/bench/wp_csv.h"

using metrosync::testing_support::benchRig;

namespace mb = metrosync::bench;
namespace ts = metrosync::testing_support;
namespace fs = std::filesystem;

namespace {

// The peer's arguments as flag -> list of numbers.
std::map<std::string, std::vector<double>> argMap(const std::vector<std::string>& args) {
  std::map<std::string, std::vector<double>> m;
  for (size_t k = 0; k + 1 < args.size(); k += 2) {
    std::stringstream ss(args[k + 1]);
    for (std::string item; std::getline(ss, item, ',');) m[args[k]].push_back(std::stod(item));
  }
  return m;
}

std::vector<double> jsonList(const nlohmann::json& j) {
  return j.get<std::vector<double>>();
}

// A stand-in peer: logs its arguments to `log`, prints one JSON line for N = 2.
std::string fakePeer(const fs::path& dir, const fs::path& log) {
  const fs::path p = dir / "fake-peer.sh";
  std::ofstream(p)
      << "#!/bin/sh\necho \"$@\" >> '" << log.string() << "'\n"
      << "echo 'peer: diagnostics on stderr' >&2\n"
      << "echo '{\"N\": 2, \"method\": \"rkf78\", \"rtol\": 1e-08, \"atol\": 1e-08, "
         "\"t\": 410.95890410958907, \"state\": [0.5, -0.5, 1.5, -1.5, 99, 2.5], "
         "\"mode\": \"slip+\", \"wall_ms\": 2.5, \"cpu_ms\": 1.25, \"wall_ms_runs\": "
         "[2.5], \"steps\": 100, \"rhs_calls\": 1300, \"events\": 40, \"restarts\": 40, "
         "\"kicks\": [3, 4], \"platform_events\": 5, \"stick_to_slip\": 1, "
         "\"slip_stops\": 2, \"stick_time\": 0}'\n";
  ::chmod(p.c_str(), 0755);
  return p.string();
}

}  // namespace

TEST(PeerScene, APhysicalRigGivesTheScaledParametersOfScale) {
  for (const char* name : {"experiment-short", "n8"}) {
    const mb::Scene scene = mb::loadScene(benchRig(name));
    const auto args = argMap(mb::peerSceneArguments(scene));
    const auto r = ts::runMetrosync("scale " + ts::shellQuote(benchRig(name)) + " --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_DOUBLE_EQ(args.at("--eps").at(0), j.at("epsilon").get<double>()) << name;
    EXPECT_DOUBLE_EQ(args.at("--mu").at(0), j.at("mu").get<double>()) << name;
    const std::vector<std::pair<const char*, const char*>> lists = {{"--nu", "nu"},
                                                                    {"--J", "J"},
                                                                    {"--thc", "theta_c"},
                                                                    {"--alpha", "alpha"},
                                                                    {"--zeta", "zeta"}};
    for (const auto& [flag, key] : lists) {
      const std::vector<double> want = jsonList(j.at(key));
      ASSERT_EQ(args.at(flag).size(), want.size()) << name << " " << flag;
      for (size_t i = 0; i < want.size(); ++i)
        EXPECT_DOUBLE_EQ(args.at(flag)[i], want[i]) << name << " " << flag << " " << i;
    }
  }
}

TEST(PeerScene, TheStartAndTheEndInScaledUnits) {
  // experiment-short: A at 0.785 rad at rest, B at -0.785 rad moving at 0.25 rad/s, the platform
  // at rest; 9.815 s. Scaled: angles / sqrt(eps), rates / (sqrt(eps) omega0), t = t-bar omega0,
  // with eps and 1/omega0 as `metrosync scale --json` prints them
  const mb::Scene scene = mb::loadScene(benchRig("experiment-short"));
  const auto r =
      ts::runMetrosync("scale " + ts::shellQuote(benchRig("experiment-short")) + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const double se = std::sqrt(j.at("epsilon").get<double>()),
               ts_ = j.at("time_scale").get<double>();
  const auto args = argMap(mb::peerSceneArguments(scene));
  const std::vector<double> want = {0.785 / se, -0.785 / se, 0.0, 0.25 * ts_ / se, 0.0, 0.0};
  ASSERT_EQ(args.at("--y0").size(), want.size());
  for (size_t k = 0; k < want.size(); ++k)
    EXPECT_NEAR(args.at("--y0")[k], want[k], 1e-14 * (1 + std::abs(want[k]))) << k;
  EXPECT_NEAR(args.at("--t_end").at(0), 9.815 / ts_, 1e-12 * 9.815 / ts_);

  // a scaled rig: its own numbers (peer-n2 is the peer's README scene)
  const auto p = argMap(mb::peerSceneArguments(mb::loadScene(benchRig("peer-n2"))));
  EXPECT_DOUBLE_EQ(p.at("--eps")[0], 0.073);
  EXPECT_DOUBLE_EQ(p.at("--mu")[0], 0.23);
  EXPECT_NEAR(p.at("--alpha")[1], 0.1, 1e-13);  // through the equivalent physical system
  EXPECT_NEAR(p.at("--nu")[1], 0.65, 1e-15);
  EXPECT_NEAR(p.at("--J")[0], 3.14, 1e-14);
  EXPECT_NEAR(p.at("--thc")[0], 0.9, 1e-15);
  const std::vector<double> y0 = {2.9 * std::sin(0.3), 0.0, 2.9 * std::cos(0.3), 2.5, 0.0, 0.0};
  for (size_t k = 0; k < y0.size(); ++k) EXPECT_NEAR(p.at("--y0")[k], y0[k], 1e-14) << k;
  EXPECT_NEAR(p.at("--t_end")[0], 30 / 0.073, 1e-12);
}

TEST(PeerScene, WhatThePeerLacksIsSaid) {
  EXPECT_EQ(mb::peerUnsupported(mb::loadScene(benchRig("peer-n8"))), "");
  const mb::Scene n32 = mb::loadScene(benchRig("n32"));
  EXPECT_NE(mb::peerUnsupported(n32).find("N = 32"), std::string::npos);
  EXPECT_THROW(mb::peerSceneArguments(n32), std::invalid_argument);
  const mb::Scene base = mb::loadScene(benchRig("experiment-short"));
  const auto why = [&](auto change) {
    metrosync::Rig rig = base.rig;
    change(rig);
    return mb::peerUnsupported(mb::sceneFromRig("x", rig));
  };
  EXPECT_NE(why([](metrosync::Rig& r) { r.metronomes[1].locked = true; }).find("locked"),
            std::string::npos);
  EXPECT_NE(why([](metrosync::Rig& r) { r.platform.spring_N_m = 3; }).find("spring"),
            std::string::npos);
  EXPECT_NE(why([](metrosync::Rig& r) {
              r.platform.friction = metrosync::FrictionLaw::viscous(0.05);
            }).find("viscous"),
            std::string::npos);
  EXPECT_NE(why([](metrosync::Rig& r) {
              r.platform.friction = metrosync::FrictionLaw::fixed();
            }).find("fixed"),
            std::string::npos);
  // static friction above kinetic: the peer has Coulomb's law only
  EXPECT_NE(
      why([](metrosync::Rig& r) {
        r.platform.friction = metrosync::FrictionLaw(metrosync::staticCoulombLaw(), {1e-3, 2e-3});
      }).find("static friction"),
      std::string::npos);
  // no friction at all is the peer's free platform (mu = 0)
  EXPECT_EQ(why([](metrosync::Rig& r) { r.platform.friction = metrosync::FrictionLaw::none(); }),
            "");
  metrosync::Rig none = base.rig;
  none.platform.friction = metrosync::FrictionLaw::none();
  EXPECT_EQ(argMap(mb::peerSceneArguments(mb::sceneFromRig("x", none))).at("--mu")[0], 0.0);
}

TEST(PeerScene, ThePeersStateBecomesTheBenchsFinalState) {
  // th_1, th_2, th'_1, th'_2, x, x'  ->  x', th_1, th'_1, th_2, th'_2
  EXPECT_EQ(mb::benchFinalState({1, 2, 3, 4, 5, 6}), (std::vector<double>{6, 1, 3, 2, 4}));
  EXPECT_TRUE(mb::benchFinalState({1, 2, 3}).empty());
}

TEST(CarefulPeerMethod, RunsAStandInPeerAndReadsItsAnswer) {
  const fs::path dir = ts::scratchDir("bench", "fakepeer", true);
  const fs::path log = dir / "args.log";
  const std::string peer = fakePeer(dir, log);
  const std::string bench = ts::shellQuote(METROSYNC_BENCH_BINARY);
  const auto r = ts::runCommand(
      bench + " precision --scene " + ts::shellQuote(benchRig("peer-n2")) + " --scene " +
      ts::shellQuote(benchRig("n32")) +
      " --methods direct:dopri5,peer:rkf78 --accuracies 1e-8 --repeat 3 --max-load 0 --peer " +
      ts::shellQuote(peer) +
      " --reference direct:verner76:1e-12 --cross-check direct:verner65:1e-10 --out " +
      ts::shellQuote((dir / "out").string()));
  ASSERT_EQ(r.code, 0) << r.err;
  // the peer was called once on peer-n2 (never on n32: N = 32), with the scene and the method
  const std::string args = ts::slurp(log.string());
  EXPECT_EQ(std::count(args.begin(), args.end(), '\n'), 1) << args;
  for (const char* want : {"--eps 0.072999999999999995 --mu 0.23000000000000001",
                           "--method rkf78 --rtol 1e-08 --atol 1e-08 --repeat 3"})
    EXPECT_NE(args.find(want), std::string::npos) << want << "\n" << args;
  const auto scenes = mb::parseWorkPrecisionCsv(
      ts::slurp((dir / "out" / "wp-peer-n2.csv").string()), "wp-peer-n2.csv");
  ASSERT_EQ(scenes.size(), 1u);
  ASSERT_EQ(scenes[0].peer.size(), 1u);
  const mb::SidePoint& p = scenes[0].peer[0];
  EXPECT_EQ(p.runs, 3);
  EXPECT_DOUBLE_EQ(p.cpu_s, 1.25e-3);
  EXPECT_DOUBLE_EQ(p.cpu_final_s, 1.25e-3);
  EXPECT_DOUBLE_EQ(p.wall_s, 2.5e-3);
  EXPECT_TRUE(std::isnan(p.err_envelope)) << "the peer reports no envelope";
  EXPECT_GT(p.err_final, 0.1) << "the stand-in's state is far from the reference";
  // the direct engine's runs without samples end where its recording runs do, bit for bit
  const std::string csv = ts::slurp((dir / "out" / "wp-peer-n2.csv").string());
  const size_t at = csv.find("peer-n2,2,65.4061,direct,dopri5,1e-08,");
  ASSERT_NE(at, std::string::npos) << csv;
  const auto f = metrosync::csvCells(csv.substr(at, csv.find('\n', at) - at));
  const auto head = metrosync::csvCells(csv.substr(0, csv.find('\n')));
  ASSERT_EQ(f.size(), head.size()) << csv;
  auto column = [&](const std::string& name) {
    const auto k = std::find(head.begin(), head.end(), name);
    return k == head.end() ? std::string("(no column " + name + ")") : f[k - head.begin()];
  };
  EXPECT_EQ(column("final_sampled_diff"), "0");
  EXPECT_GT(std::stod(column("cpu_final_median_s")), 0.0);
  EXPECT_EQ(column("engine_median_s"), "") << "the engine's own timing is `run`'s alone";
  const auto n32 =
      mb::parseWorkPrecisionCsv(ts::slurp((dir / "out" / "wp-n32.csv").string()), "wp-n32.csv");
  EXPECT_NE(n32.at(0).peer_skipped.find("N = 32"), std::string::npos);
  const std::string md = ts::slurp((dir / "out" / "ratios.md").string());
  EXPECT_NE(md.find("| n32 | 32 | peer not run: N = 32"), std::string::npos) << md;
  fs::remove_all(dir);
}

TEST(CarefulPeerMethod, AMissingPeerIsSaidClearly) {
  const std::string bench = ts::shellQuote(METROSYNC_BENCH_BINARY);
  const auto where = ts::runCommand(bench + " peer --peer /nonexistent/peer");
  EXPECT_EQ(where.code, 1);
  EXPECT_NE(where.err.find("/nonexistent/peer, which is not an executable file"), std::string::npos)
      << where.err;
  const auto r =
      ts::runCommand(bench + " precision --scene " + ts::shellQuote(benchRig("peer-n2")) +
                     " --methods peer:rkf78 --peer /nonexistent/peer --out /tmp/x");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("'peer:rkf78': --peer names /nonexistent/peer"), std::string::npos) << r.err;
  // the scripts looked for: beside this tree, and beside a worktree's main checkout
  const auto scripts = mb::peerBuildScripts("/a/b/repo");
  ASSERT_GE(scripts.size(), 1u);
  EXPECT_EQ(scripts[0], "/a/b/shared/peer/build.sh");
}

TEST(CarefulPeerMethod, AgreesWithTheReferenceWhereThePeerIsFound) {
  // the physical rig and the peer's scaled equations are the same system: at tight tolerance
  // the peer's final state is the direct engine's, far below the errors the bench compares
  if (mb::peerLocation().path.empty()) GTEST_SKIP() << mb::peerLocation().missing;
  for (const char* name : {"peer-n2", "experiment-short"}) {
    const mb::Scene scene = mb::loadScene(benchRig(name));
    const mb::RunResult ref = mb::runOnce(scene, mb::parseMethod("direct:verner76:1e-12"), 0);
    const mb::RunResult peer = mb::runOnce(scene, mb::parseMethod("peer:rkf78:1e-12"), 0);
    ASSERT_TRUE(peer.complete) << peer.failure;
    EXPECT_EQ(peer.counts.escapements, ref.counts.escapements) << name;
    EXPECT_LT(mb::compareRuns(peer, ref).final_state, 1e-9) << name;
  }
}

TEST(RunCost, TimesRunAgainstItsEngine) {
  const fs::path dir = ts::scratchDir("bench", "runcost", true);
  const auto r = ts::runCommand(
      ts::shellQuote(METROSYNC_BENCH_BINARY) + " runcost --metrosync " +
      ts::shellQuote(METROSYNC_BINARY) + " --scene " + ts::shellQuote(benchRig("peer-n2")) +
      " --scene default --variant '' --variant 'simulation.sample=100' "
      "--repeat 2 --max-load 0 --quiet --tmp " +
      ts::shellQuote(dir.string()) + " --out " + ts::shellQuote(dir.string()));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string csv = ts::slurp((dir / "run.csv").string());
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);
  const std::vector<std::string> header = metrosync::csvCells(line);
  int rows = 0;
  for (; std::getline(lines, line); ++rows) {
    const auto f = metrosync::csvCells(line);
    ASSERT_EQ(f.size(), header.size()) << line;
    std::map<std::string, std::string> c;
    for (size_t k = 0; k < f.size(); ++k) c[header[k]] = f[k];
    EXPECT_EQ(c["runs"], "2") << line;
    // the process holds the integration
    EXPECT_GT(std::stod(c["process_wall_s"]), std::stod(c["wall_seconds"]));
    EXPECT_EQ(c["failure"], "") << line;
    // the engine summary.json names, run again in the bench's process with recording off
    EXPECT_EQ(c["engine"], "direct:verner76:1e-08") << line;
    EXPECT_GT(std::stod(c["engine_alone_s"]), 0.0) << line;
    EXPECT_NEAR(std::stod(c["wall_over_alone"]),
                std::stod(c["wall_seconds"]) / std::stod(c["engine_alone_s"]),
                1e-4 * std::stod(c["wall_over_alone"]));
    if (c["engine_seconds"].empty()) continue;      // every run's split impossible (counted)
    EXPECT_GE(std::stod(c["ratio"]), 1.0) << line;  // wall_seconds / engine_seconds
    EXPECT_LE(std::stod(c["ratio_min"]), std::stod(c["ratio_max"])) << line;
  }
  EXPECT_EQ(rows, 4) << csv;  // two scenes (the default rig, the built-in one), two variants
  EXPECT_NE(csv.find("\ndefault,simulation.sample=100,"), std::string::npos) << csv;
  EXPECT_NE(ts::slurp((dir / "run.md").string()).find("target <= 1.15"), std::string::npos);
  fs::remove_all(dir);
}

TEST(MapTiming, TheSweepsOfTheIssue) {
  mb::MapOptions o;
  o.metrosync = "m";
  EXPECT_EQ(mb::mapSweepArgs(o, "full"),
            (std::vector<std::string>{"m", "sweep", "yaml/rigs/experiment-map.yaml", "--model",
                                      "full", "--vary", "platform.friction.mu=0:0.8:64", "--vary",
                                      "metronomes.0.start.phi=0:6.283185307179586:64:open",
                                      "--jobs", "2", "--no-plot", "-q"}));
  EXPECT_EQ(mb::mapSweepArgs(o, "slow").at(6), "platform.friction.mu=0:0.8:100");
  EXPECT_THROW(mb::mapSweepArgs(o, "medium"), std::invalid_argument);
  // timed end to end on a stand-in that does nothing
  const fs::path dir = ts::scratchDir("bench", "maps", true);
  const auto r = ts::runCommand(ts::shellQuote(METROSYNC_BENCH_BINARY) +
                                " maps --metrosync /bin/true --maps slow --max-load 0 --quiet "
                                "--out " +
                                ts::shellQuote(dir.string()));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string csv = ts::slurp((dir / "maps.csv").string());
  EXPECT_NE(csv.find("\nslow,10000,1,"), std::string::npos) << csv;
  EXPECT_NE(ts::slurp((dir / "maps.md").string()).find("<= 3 s: met"), std::string::npos);
  fs::remove_all(dir);
}
