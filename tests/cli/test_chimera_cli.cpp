// The network label's chimera (docs/regimes.md "Networks") on simulated runs: the shipped
// two-boards rig, whose left pair locks near antiphase (r ~ 0) and right pair in phase, is no
// chimera (both boards coherent; main labelled it `chimera` from r alone), and the shipped
// chimera-swings rig (two swings of 15 after Martens et al. 2013) is one as shipped and at 1.5x
// its duration, with the left swing locked and the right one incoherent.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "tests/common/run_metrosync.h"

namespace metrosync {
namespace {

using testing_support::runMetrosync;
using testing_support::scratchDir;
using testing_support::shellQuote;
using testing_support::slurp;

const std::string kRigs = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/";

nlohmann::json runSummary(const std::string& rig, const std::string& name,
                          const std::string& extra = "") {
  const std::string out = scratchDir("chimera", name);
  const auto r = runMetrosync("run " + shellQuote(kRigs + rig) + " --quiet --no-plot " + extra +
                              " --out " + shellQuote(out));
  EXPECT_EQ(r.code, 0) << r.err;
  return nlohmann::json::parse(slurp(out + "/summary.json"));
}

TEST(ChimeraLabel, BoardsLockedInPhaseAndNearAntiphaseAreNoChimera) {
  const nlohmann::json s = runSummary("two-boards-rollers.yaml", "boards");
  // what makes the r-only rule say chimera: one board's r near 1, the other's far below 0.5
  EXPECT_GT(s["platforms"]["right"]["r"].get<double>(), 0.9);
  EXPECT_LT(s["platforms"]["left"]["r"].get<double>(), 0.5);
  EXPECT_EQ(s["platforms"]["right"]["regime"], "in-phase");
  EXPECT_EQ(s["network"]["regime"], "coherent-groups");
}

TEST(ChimeraLabel, ShippedChimeraSwingsStayAChimeraAtOneAndAHalfTheirLength) {
  for (const char* duration : {"300", "450"}) {  // the rig's duration, and 1.5x
    const nlohmann::json s = runSummary("chimera-swings.yaml", std::string("swings") + duration,
                                        std::string("--set simulation.duration=") + duration);
    EXPECT_EQ(s["network"]["regime"], "chimera") << duration;
    EXPECT_EQ(s["platforms"]["left"]["regime"], "in-phase") << duration;
    // the right swing is neither in phase nor dead: its metronomes drift against each other
    EXPECT_EQ(s["platforms"]["right"]["regime"], "drift") << duration;
  }
}

// Issue 37: a network whose platforms each said `unsettled` was labelled `coherent-groups`
// (two-swings.yaml as shipped) or `chimera` (two-boards-rollers.yaml stopped after 0.5 s, shorter
// than 5 fast periods). A platform's verdict and its group's locking now agree, and a run too
// short to judge is `unsettled` as a network too.
TEST(ChimeraLabel, APlatformsVerdictAgreesWithTheNetworkLabel) {
  const nlohmann::json swings = runSummary("two-swings.yaml", "two-swings");
  EXPECT_EQ(swings["network"]["regime"], "coherent-groups");
  for (const auto& [name, p] : swings["platforms"].items()) {
    const std::string regime = p["regime"];
    EXPECT_EQ(regime.find("unsettled"), std::string::npos) << name << ": " << regime;
    EXPECT_EQ(regime.find("drift"), std::string::npos) << name << ": " << regime;
  }
  const nlohmann::json short_run =
      runSummary("two-boards-rollers.yaml", "short", "--set simulation.duration=0.5");
  for (const auto& [name, p] : short_run["platforms"].items())
    EXPECT_EQ(p["regime"], "unsettled") << name;
  EXPECT_EQ(short_run["network"]["regime"], "unsettled");
}

}  // namespace
}  // namespace metrosync
