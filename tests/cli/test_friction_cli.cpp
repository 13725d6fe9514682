// Friction laws on the command line (docs/friction.md). Static friction above kinetic: a bad
// mu_static is refused with exit 2 naming file, line, key and value, nothing written; the slow
// flow refuses mu_static > mu (run --model slow, compare, continue, basin --model slow) with exit
// 2 before writing anything, and takes mu_static == mu; the full model runs it on both engines.
// Stribeck friction: its keys read like any law's (the exponent defaults to 2, a velocity of 0
// is refused), the slow flow refuses it naming the law, the full model runs it on both engines.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/common/run_metrosync.h"

namespace metrosync {
namespace {

namespace fs = std::filesystem;
using testing_support::CommandResult;
using testing_support::runMetrosync;
using testing_support::scratchDir;
using testing_support::shellQuote;
using testing_support::slurp;

const std::string kExperiment = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/experiment.yaml";

const std::string kStribeck =
    "{law: stribeck, mu: 6.5e-4, mu_static: 1.3e-3, stribeck_velocity: 2e-3}";

// The experiment with `friction` on line 9 (its platform.friction line), in a scratch file.
std::string rigWithFriction(const std::string& name, const std::string& friction) {
  std::ifstream in(kExperiment);
  std::string text, line;
  for (int n = 1; std::getline(in, line); ++n)
    text += (line.rfind("  friction:", 0) == 0 ? "  friction: " + friction : line) + "\n";
  const std::string path = scratchDir("friction", name, true) + "/rig.yaml";
  std::ofstream(path) << text;
  return path;
}

TEST(FrictionCli, BadStaticCoefficientIsRefusedWithFileLineAndKey) {
  struct Case {
    const char* friction;
    const char* says;
  };
  for (const Case& c :
       {Case{"{law: coulomb, mu: 6.5e-4, mu_static: 1e-4}",
             "rig.yaml:9:51: platform.friction.mu_static = 1e-4: must be >= mu"},
        Case{"{law: coulomb, mu: 6.5e-4, mu_static: -1}",
             "rig.yaml:9:51: platform.friction.mu_static = -1: must be >= 0"},
        Case{"{law: viscous, c: 0.1, mu_static: 0.2}",
             "rig.yaml:9:47: platform.friction.mu_static = 0.2: only with law: coulomb"}}) {
    SCOPED_TRACE(c.friction);
    const std::string rig = rigWithFriction("bad", c.friction);
    const std::string out = fs::path(rig).parent_path().string() + "/out";
    const CommandResult r = runMetrosync("run " + shellQuote(rig) + " -q --out " + shellQuote(out));
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << "nothing written";
  }
  const CommandResult set =
      runMetrosync("run " + shellQuote(kExperiment) + " -q --set platform.friction.mu_static=1e-5");
  EXPECT_EQ(set.code, 2);
  EXPECT_NE(set.err.find("--set platform.friction.mu_static=1e-5: platform.friction.mu_static = "
                         "1e-5: must be >= mu"),
            std::string::npos)
      << set.err;
}

TEST(FrictionCli, TheSlowFlowRefusesStaticAboveKinetic) {
  const std::string rig = rigWithFriction("slow", "{law: coulomb, mu: 6.5e-4, mu_static: 1e-3}");
  const std::string dir = fs::path(rig).parent_path().string();
  for (const std::string& cmd :
       {"run " + shellQuote(rig) + " --model slow", "compare " + shellQuote(rig),
        "continue " + shellQuote(rig) + " --param platform.friction.mu --to 2e-3",
        "basin " + shellQuote(rig) + " --random metronomes.0.start.angle=0:0.8 --samples 2"}) {
    SCOPED_TRACE(cmd);
    const std::string out = dir + "/out";
    const CommandResult r = runMetrosync(cmd + " -q --out " + shellQuote(out));
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("rig.yaml: the slow flow: platform.friction.mu_static > mu"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("--model full"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << "nothing written";
  }
  // equal coefficients are Coulomb's law: the slow flow runs them, to the same envelope
  const std::string equal =
      rigWithFriction("equal", "{law: coulomb, mu: 6.5e-4, mu_static: 6.5e-4}");
  const std::string a = dir + "/a", b = dir + "/b";
  ASSERT_EQ(runMetrosync("run " + shellQuote(equal) + " --model slow -q --no-plot --out " + a).code,
            0);
  ASSERT_EQ(
      runMetrosync("run " + shellQuote(kExperiment) + " --model slow -q --no-plot --out " + b).code,
      0);
  EXPECT_EQ(slurp(a + "/envelope.csv"), slurp(b + "/envelope.csv"));
}

TEST(FrictionCli, TheFullModelRunsItOnBothEngines) {
  for (const std::string engine : {"direct", "simbody"}) {
    SCOPED_TRACE(engine);
    const std::string out = scratchDir("friction", "full-" + engine);
    const CommandResult r = runMetrosync("run " + shellQuote(kExperiment) + " --engine " + engine +
                                         " --set platform.friction.mu_static=1.3e-3 --set "
                                         "simulation.duration=5 -q --no-plot --out " +
                                         shellQuote(out));
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json s = nlohmann::json::parse(slurp(out + "/summary.json"));
    EXPECT_EQ(s["resolved_rig"]["platform"]["friction"]["mu_static"].get<double>(), 1.3e-3);
    EXPECT_GT(s["counts"]["stick_slip"].get<long>(), 0) << s.dump();
  }
}

TEST(StribeckCli, BadParametersAreRefusedWithFileLineAndKey) {
  struct Case {
    const char* friction;
    const char* says;
  };
  for (const Case& c :
       {Case{"{law: stribeck, mu: 6.5e-4, mu_static: 1.3e-3, stribeck_velocity: 0}",
             "platform.friction.stribeck_velocity = 0: must be > 0"},
        Case{"{law: stribeck, mu: 6.5e-4, mu_static: 1e-4, stribeck_velocity: 2e-3}",
             "platform.friction.mu_static = 1e-4: must be >= mu"},
        Case{"{law: stribeck, mu: 6.5e-4, mu_static: 1.3e-3}",
             "platform.friction.stribeck_velocity: missing (V in m/s"}}) {
    SCOPED_TRACE(c.friction);
    const std::string rig = rigWithFriction("stribeck-bad", c.friction);
    const std::string out = fs::path(rig).parent_path().string() + "/out";
    const CommandResult r = runMetrosync("run " + shellQuote(rig) + " -q --out " + shellQuote(out));
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("rig.yaml:9:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << "nothing written";
  }
}

TEST(StribeckCli, TheSlowFlowRefusesItNamingTheLaw) {
  const std::string rig = rigWithFriction("stribeck-slow", kStribeck);
  const std::string dir = fs::path(rig).parent_path().string();
  for (const std::string& cmd :
       {"run " + shellQuote(rig) + " --model slow", "compare " + shellQuote(rig)}) {
    SCOPED_TRACE(cmd);
    const std::string out = dir + "/out";
    const CommandResult r = runMetrosync(cmd + " -q --out " + shellQuote(out));
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("rig.yaml: the slow flow: platform.friction: {law: stribeck}"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("--model full"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << "nothing written";
  }
}

TEST(StribeckCli, TheFullModelRunsItOnBothEnginesWithTheDefaultExponent) {
  const std::string rig = rigWithFriction("stribeck-full", kStribeck);
  for (const std::string engine : {"direct", "simbody"}) {
    SCOPED_TRACE(engine);
    const std::string out = scratchDir("friction", "stribeck-full-" + engine);
    const CommandResult r =
        runMetrosync("run " + shellQuote(rig) + " --engine " + engine +
                     " --set simulation.duration=5 -q --no-plot --out " + shellQuote(out));
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json s = nlohmann::json::parse(slurp(out + "/summary.json"));
    const nlohmann::json& f = s["resolved_rig"]["platform"]["friction"];
    EXPECT_EQ(f["law"], "stribeck");
    EXPECT_EQ(f["stribeck_velocity"].get<double>(), 2e-3);
    EXPECT_FALSE(f.contains("exponent")) << "the file's keys, as written";
    EXPECT_EQ(s["scaled"]["exponent"].get<double>(), 2.0) << "the default, a pure number";
    EXPECT_GT(s["counts"]["stick_slip"].get<long>(), 0) << s.dump();
  }
}

}  // namespace
}  // namespace metrosync
