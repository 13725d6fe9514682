// `metrosync continue --model full` end to end: the files and their columns on the paper's f4.3
// rig, and bad input refused with exit 2, a message naming what is wrong, and nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "tests/common/run_metrosync.h"

namespace metrosync {
namespace {

using testing_support::runMetrosync;
using testing_support::scratchDir;
using testing_support::shellQuote;
using testing_support::slurp;

std::string rig(const std::string& name) {
  return shellQuote(std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/" + name);
}

TEST(ContinueFullCli, F43FilesAndTheirColumns) {
  const std::string out = scratchDir("continue-full", "f43");
  const auto r = runMetrosync("continue " + rig("paper/f4.3-mu0.2.yaml") +
                              " --model full --param platform.friction.mu --to 0.3 -q --out " +
                              shellQuote(out));
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream csv(slurp(out + "/branches.csv"));
  std::string header, row;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "branch,platform.friction.mu,period,section_xdot,section_theta_2,section_thetadot_1,"
            "section_thetadot_2,A_1,A_2,psi_2,max_multiplier,stable,ticks_1,ticks_2,stick_slip,"
            "reversals,at_ticks");
  int rows = 0;
  while (std::getline(csv, row)) ++rows;
  EXPECT_GT(rows, 20);
  const auto bif = nlohmann::json::parse(slurp(out + "/bifurcations.json"));
  std::set<std::string> types;
  for (const auto& b : bif) {
    types.insert(b["type"].get<std::string>());
    EXPECT_EQ(b["param"], "platform.friction.mu");
    EXPECT_EQ(b["multipliers"].size(), 4u);  // 2N: the section's coordinates
    EXPECT_EQ(b["A"].size(), 2u);
    EXPECT_GT(b["period"].get<double>(), 6.0);
  }
  EXPECT_TRUE(types.count("torus") && types.count("fold"));
  const auto summary = nlohmann::json::parse(slurp(out + "/summary.json"));
  EXPECT_EQ(summary["model"], "full");
  EXPECT_EQ(summary["bifurcations"]["torus"], 1);
  EXPECT_EQ(summary["branches"][0]["symmetry"], "in-phase");
}

struct Bad {
  const char* name;
  std::string args;
  const char* says;
};

class ContinueFullBadInput : public ::testing::TestWithParam<Bad> {};

TEST_P(ContinueFullBadInput, ExitsTwoAndWritesNothing) {
  const std::string out = scratchDir("continue-full", GetParam().name);
  const auto r =
      runMetrosync("continue " + GetParam().args + " --model full --out " + shellQuote(out));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(GetParam().says), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ContinueFullBadInput,
    ::testing::Values(
        Bad{"unknown_key", rig("paper/f4.3-mu0.2.yaml") + " --param platform.friction.muu --to 0.3",
            "platform.friction.muu: unknown key"},
        Bad{"no_effect", rig("paper/f4.3-mu0.2.yaml") + " --param simulation.tau --to 400",
            "has no effect on the full model"},
        Bad{"drift", rig("regimes/drift-pair.yaml") + " --param platform.friction.mu --to 0.2",
            "does not settle onto a periodic orbit"},
        Bad{"death", rig("paper/f4.3-mu0.4.yaml") + " --param platform.friction.mu --to 0.5",
            "every metronome has stopped"},
        Bad{"slow_only",
            rig("paper/f4.3-mu0.2.yaml") + " --param platform.friction.mu --to 0.3 --all",
            "--all: not with --model full"}),
    [](const ::testing::TestParamInfo<Bad>& i) { return i.param.name; });

}  // namespace
}  // namespace metrosync
