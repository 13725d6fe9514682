// `metrosync run` on networks of platforms (docs/networks.md): the issue's file columns and
// summary keys exactly, refusals with exit 2 and nothing written, and a network of one that runs
// today's code path (its files byte for byte those of the same rig in today's form).
#include <gtest/gtest.h>

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

const std::string kRigs = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/";

std::string firstLine(const std::string& path) {
  std::ifstream in(path);
  std::string l;
  std::getline(in, l);
  return l;
}

TEST(NetworkCli, RunWritesTheIssuesColumnsAndKeys) {
  const std::string out = scratchDir("net", "run");
  const auto r = runMetrosync("run " + shellQuote(kRigs + "two-boards-rollers.yaml") +
                              " --quiet --set simulation.duration=3 --out " + shellQuote(out));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(firstLine(out + "/trajectory.csv"),
            "t,x_left,xdot_left,platform_left,x_right,xdot_right,platform_right,theta_1,"
            "thetadot_1,theta_2,thetadot_2,theta_3,thetadot_3,theta_4,thetadot_4");
  // SPEC's columns, then t_s (seconds: a network is a physical rig)
  EXPECT_EQ(firstLine(out + "/envelope.csv"), "tau,A_1,A_2,A_3,A_4,psi_2,psi_3,psi_4,r,t_s");
  EXPECT_EQ(firstLine(out + "/order.csv"), "tau,r_left,Phi_left,r_right,Phi_right,r,Phi,t_s");
  const nlohmann::json s = nlohmann::json::parse(slurp(out + "/summary.json"));
  EXPECT_EQ(s["platforms"]["left"]["metronomes"], nlohmann::json({1, 2}));
  EXPECT_EQ(s["platforms"]["right"]["metronomes"], nlohmann::json({3, 4}));
  for (const char* p : {"left", "right"}) {
    EXPECT_TRUE(s["platforms"][p]["regime"].is_string());
    const double r_p = s["platforms"][p]["r"];
    EXPECT_TRUE(r_p >= 0 && r_p <= 1) << r_p;
  }
  EXPECT_TRUE(s["network"]["regime"].is_string());
  EXPECT_TRUE(s["complete"].get<bool>());
  // the ledger closes (the run's own check, reported)
  EXPECT_LT(std::abs(s["energy"]["relative_residual"].get<double>()), 1e-6);
}

TEST(NetworkCli, SlowFlowIsRefusedWithNothingWritten) {
  for (const std::string opt : {"--model slow", "--engine slowflow"}) {
    const std::string out = scratchDir("net", "refused");
    const auto r = runMetrosync("run " + shellQuote(kRigs + "two-swings.yaml") + " " + opt +
                                " --out " + shellQuote(out));
    EXPECT_EQ(r.code, 2) << opt;
    EXPECT_NE(r.err.find("a network of 2 platforms"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << opt;
  }
}

TEST(NetworkCli, SimbodyEngineWritesTheSameFilesAsTheDirectEngine) {
  const std::string d = scratchDir("net", "engines", true);
  std::vector<nlohmann::json> s;
  for (const std::string engine : {"direct", "simbody"}) {
    const auto r = runMetrosync(
        "run " + shellQuote(kRigs + "two-boards-rollers.yaml") + " --quiet --no-plot --engine " +
        engine + " --set simulation.duration=2 --out " + shellQuote(d + "/" + engine));
    ASSERT_EQ(r.code, 0) << r.err;
    s.push_back(nlohmann::json::parse(slurp(d + "/" + engine + "/summary.json")));
    EXPECT_EQ(s.back()["engine"], engine);
  }
  for (const char* f : {"trajectory.csv", "envelope.csv", "order.csv"})
    EXPECT_EQ(firstLine(d + "/direct/" + f), firstLine(d + "/simbody/" + f)) << f;
  EXPECT_EQ(s[0]["network"]["regime"], s[1]["network"]["regime"]);
  EXPECT_NEAR(s[0]["network"]["r"].get<double>(), s[1]["network"]["r"].get<double>(), 1e-6);
  EXPECT_EQ(s[0]["counts"]["escapements"], s[1]["counts"]["escapements"]);
  EXPECT_EQ(s[0]["counts"]["stick_slip"], s[1]["counts"]["stick_slip"]);
}

TEST(NetworkCli, BadNetworkExitsTwoNamingFileKeyAndLine) {
  const std::string dir = scratchDir("net", "bad", true);
  std::string text = slurp(kRigs + "two-boards-rollers.yaml");
  const std::string from = "between: [left, right]";
  text.replace(text.find(from), from.size(), "between: [left, middle]");
  std::ofstream(dir + "/bad.yaml") << text;
  const auto r =
      runMetrosync("run " + shellQuote(dir + "/bad.yaml") + " --out " + shellQuote(dir + "/out"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("bad.yaml:21:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("couplings.0.between.1 = middle"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
}

TEST(NetworkCli, NetworkOfOneRunsTodaysPathByteForByte) {
  const std::string dir = scratchDir("net", "one", true);
  // board-on-springs.yaml in today's form
  std::ofstream(dir + "/today.yaml") << R"(units: physical
name: board-on-springs
gravity: 9.81
platform:
  mass: 0.1432
  friction: {law: coulomb, mu: 6.5e-4}
  spring: {k: 10.0}
start: {x: 0.02, v: 0.0}
metronomes:
  - {name: A, box_mass: 0.0602, pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}, locked: true}
  - {name: B, box_mass: 0.0602, pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}, locked: true}
simulation:
  duration: 20
)";
  const auto a = runMetrosync("run " + shellQuote(kRigs + "board-on-springs.yaml") +
                              " --quiet --out " + shellQuote(dir + "/a"));
  const auto b = runMetrosync("run " + shellQuote(dir + "/today.yaml") + " --quiet --out " +
                              shellQuote(dir + "/b"));
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  for (const char* f : {"trajectory.csv", "envelope.csv"})
    EXPECT_EQ(slurp(dir + "/a/" + f), slurp(dir + "/b/" + f)) << f;
  EXPECT_GT(slurp(dir + "/a/trajectory.csv").size(), 1000u);
}

}  // namespace
}  // namespace metrosync
