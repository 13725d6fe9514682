// Stribeck friction on the command line (docs/friction.md): its keys read like any law's (the
// exponent defaults to 2, a velocity of 0 or a static coefficient below the kinetic is refused
// with exit 2 naming file, line, key and value), the slow flow refuses it with exit 2 naming the
// law before anything is written, and the full model runs it on both engines.
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
  while (std::getline(in, line))
    text += (line.rfind("  friction:", 0) == 0 ? "  friction: " + friction : line) + "\n";
  const std::string path = scratchDir("stribeck", name, true) + "/rig.yaml";
  std::ofstream(path) << text;
  return path;
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
    const std::string rig = rigWithFriction("bad", c.friction);
    const std::string out = fs::path(rig).parent_path().string() + "/out";
    const CommandResult r = runMetrosync("run " + shellQuote(rig) + " -q --out " + shellQuote(out));
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("rig.yaml:9:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << "nothing written";
  }
}

TEST(StribeckCli, TheSlowFlowRefusesItNamingTheLaw) {
  const std::string rig = rigWithFriction("slow", kStribeck);
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
  const std::string rig = rigWithFriction("full", kStribeck);
  for (const std::string engine : {"direct", "simbody"}) {
    SCOPED_TRACE(engine);
    const std::string out = scratchDir("stribeck", "full-" + engine);
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
