// `metrosync continue` end to end: the files and their columns on the paper's f4.4 rig, and bad
// input refused with exit 2, a message naming what is wrong, and nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/common/run_metrosync.h"

namespace metrosync {
namespace {

using testing_support::runMetrosync;
using testing_support::scratchDir;
using testing_support::shellQuote;
using testing_support::slurp;

const std::string kRig = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/paper/f4.4-alpha4.yaml";

TEST(ContinueCli, F44FilesAndTheFold) {
  const std::string out = scratchDir("continue", "f44");
  const auto r =
      runMetrosync("continue " + shellQuote(kRig) +
                   " --param metronomes.1.alpha --from 3.8 --to 4.0 -q --out " + shellQuote(out));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string csv = slurp(out + "/branches.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "branch,metronomes.1.alpha,A_1,A_2,psi_2,stable,max_real,ticking,platform,s");
  const auto bif = nlohmann::json::parse(slurp(out + "/bifurcations.json"));
  int folds = 0;
  for (const auto& b : bif) {
    EXPECT_EQ(b["param"], "metronomes.1.alpha");
    EXPECT_EQ(b["A"].size(), 2u);
    EXPECT_EQ(b["psi"].size(), 1u);
    EXPECT_EQ(b["eigenvalues"].size(), 3u);  // 2N - 1: the symmetry removed
    if (b["type"] == "fold") {
      ++folds;
      EXPECT_GT(b["value"].get<double>(), 3.9);
      EXPECT_LT(b["value"].get<double>(), 3.95);
    }
  }
  EXPECT_EQ(folds, 1);
  const auto summary = nlohmann::json::parse(slurp(out + "/summary.json"));
  EXPECT_EQ(summary["bifurcations"]["fold"], 1);
  EXPECT_EQ(summary["from"].get<double>(), 3.8);
}

TEST(ContinueCli, FoldCurveInASecondKey) {
  const std::string out = scratchDir("continue", "fold");
  const auto r = runMetrosync("continue " + shellQuote(kRig) +
                              " --param metronomes.1.alpha --from 3.8 --to 4.0 --fold "
                              "platform.friction.mu --to2 0.41 -q --out " +
                              shellQuote(out));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string csv = slurp(out + "/fold_curve.csv");
  std::istringstream lines(csv);
  std::string header, row;
  std::getline(lines, header);
  EXPECT_EQ(header, "fold,metronomes.1.alpha,platform.friction.mu,A_1,A_2,psi_2");
  int rows = 0;
  double mu_max = 0;
  while (std::getline(lines, row)) {
    ++rows;
    std::istringstream f(row);
    std::string id, alpha, mu;
    std::getline(f, id, ',');
    std::getline(f, alpha, ',');
    std::getline(f, mu, ',');
    EXPECT_EQ(id, "0");
    mu_max = std::max(mu_max, std::stod(mu));
  }
  EXPECT_GT(rows, 3);
  EXPECT_NEAR(mu_max, 0.41, 1e-9);  // the curve reaches the end of KEY2's range
  const auto summary = nlohmann::json::parse(slurp(out + "/summary.json"));
  EXPECT_EQ(summary["param2"], "platform.friction.mu");
}

struct BadCase {
  std::string args;
  std::string says;  // in the message
};

TEST(ContinueCli, BadInputExit2NothingWritten) {
  const std::vector<BadCase> cases = {
      {"--param metronomes.1.bogus --from 1 --to 2", "bogus"},
      {"--param platform.friction.law --from 1 --to 2", "platform.friction.law"},
      {"--param name --to 2", "name"},
      {"--param metronomes.1.alpha --to 4.0", "must differ from the start value"},  // the rig's
      {"--param metronomes.1.alpha --from 3.9 --to 3.9", "must differ"},
      {"--param epsilon --to 0.05", "epsilon has no effect on the slow flow"},
      {"--param metronomes.1.alpha --from 3.9 --to 4 --set simulation.tau=2", "does not settle"},
      {"--param metronomes.1.alpha --from 3.9 --to 4 --start 1,2", "expected 3 numbers"},
      {"--param metronomes.1.alpha --from 3.9 --to 4 --start 1,x,3", "not a number"},
  };
  for (const BadCase& c : cases) {
    const std::string out = scratchDir("continue", "bad");
    const auto r =
        runMetrosync("continue " + shellQuote(kRig) + " " + c.args + " --out " + shellQuote(out));
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.args;
  }
}

}  // namespace
}  // namespace metrosync
