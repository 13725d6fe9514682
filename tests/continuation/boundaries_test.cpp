// `metrosync sweep --model slow --boundaries`: the fold curve computed by continuation must be
// where the sweep's own runs (slow-flow integrations from the rig's start, independent of the
// continuation) change regime: on the f4.4 rig over (alpha, mu), below the fold curve metronome 2
// stays suppressed, above it both die. Bad uses of --boundaries exit 2 and write nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "tests/common/run_metrosync.h"

namespace metrosync {
namespace {

using testing_support::runMetrosync;
using testing_support::scratchDir;
using testing_support::shellQuote;
using testing_support::slurp;

const std::string kRig = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/paper/f4.4-alpha4.yaml";

std::vector<std::vector<std::string>> rows(const std::string& csv) {
  std::vector<std::vector<std::string>> out;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) cells.push_back(c);
    out.push_back(cells);
  }
  return out;
}

// mu on the fold curve at alpha, interpolated between its points (NaN when not covered).
double foldMu(const std::vector<std::vector<std::string>>& curve, double alpha) {
  for (size_t k = 1; k < curve.size(); ++k) {
    if (curve[k][0] != curve[k - 1][0] || curve[k][1] != "fold") continue;
    const double a0 = std::stod(curve[k - 1][2]), a1 = std::stod(curve[k][2]);
    if ((a0 - alpha) * (a1 - alpha) > 0 || a0 == a1) continue;
    const double m0 = std::stod(curve[k - 1][3]), m1 = std::stod(curve[k][3]);
    return m0 + (alpha - a0) / (a1 - a0) * (m1 - m0);
  }
  return std::nan("");
}

TEST(SweepBoundaries, FoldCurveSeparatesTheSweepsRegimes) {
  const std::string out = scratchDir("boundaries", "f44");
  const auto r = runMetrosync("sweep " + shellQuote(kRig) +
                              " --model slow --vary metronomes.1.alpha=2.5:4.5:6 --vary "
                              "platform.friction.mu=0.3:0.5:21 --boundaries -q --out " +
                              shellQuote(out));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string csv = slurp(out + "/boundaries.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "curve,type,metronomes.1.alpha,platform.friction.mu");
  const auto curve = rows(csv);
  ASSERT_GT(curve.size(), 10u);
  const nlohmann::json status = nlohmann::json::parse(slurp(out + "/sweep.json"));
  ASSERT_TRUE(status.contains("boundaries"));
  EXPECT_EQ(status["boundaries"][0]["type"], "fold");
  constexpr double kCell = 0.01;  // the mu grid's spacing: points this close to the curve are left
  int checked = 0;
  for (const auto& p : rows(slurp(out + "/regimes.csv"))) {
    const double alpha = std::stod(p[0]), mu = std::stod(p[1]);
    const double fold = foldMu(curve, alpha);
    ASSERT_FALSE(std::isnan(fold)) << "the curve does not cover alpha = " << alpha;
    if (std::abs(mu - fold) < kCell) continue;
    const std::string regime = p[2];
    EXPECT_EQ(regime, mu < fold ? "suppression" : "death")
        << "alpha " << alpha << ", mu " << mu << ", fold at mu " << fold;
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

TEST(SweepBoundaries, BadUsesExit2NothingWritten) {
  const std::vector<std::string> bad = {
      " --model full --vary metronomes.1.alpha=2.5:4.5:3 --vary platform.friction.mu=0.3:0.5:3",
      " --model slow --vary metronomes.1.alpha=2.5:4.5:3",
      " --model slow --vary metronomes.1.alpha=2.5,3,4.5 --vary platform.friction.mu=0.3:0.5:3",
      " --model slow --vary epsilon=0.05:0.07:3 --vary platform.friction.mu=0.3:0.5:3"};
  for (size_t k = 0; k < bad.size(); ++k) {
    const std::string out = scratchDir("boundaries", "bad" + std::to_string(k));
    std::filesystem::remove_all(out);
    const auto r = runMetrosync("sweep " + shellQuote(kRig) + bad[k] + " --boundaries -q --out " +
                                shellQuote(out));
    EXPECT_EQ(r.code, 2) << bad[k] << "\n" << r.err;
    EXPECT_NE(r.err.find("boundaries"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << bad[k];
  }
}

}  // namespace
}  // namespace metrosync
