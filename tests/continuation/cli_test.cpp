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
            "branch,metronomes.1.alpha,A_1,A_2,psi_2,stable,max_real,ticking,platform,s,weight");
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

// metronomes.*.nu sets both metronomes: identical metronomes stay identical along the branch (the
// in-phase state keeps A_1 = A_2), while the amplitude follows the damping; a change of metronome
// 1 alone (metronomes.0.nu) breaks the symmetry at once.
TEST(ContinueCli, WildcardKeySetsEveryMetronome) {
  const std::string rig = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/paper/f4.3-mu0.2.yaml";
  auto amplitudes = [&](const std::string& key) {
    const std::string out = scratchDir("continue", "wildcard");
    const auto r = runMetrosync("continue " + shellQuote(rig) + " --param " + key +
                                " --to 0.8 --no-cycles -q --out " + shellQuote(out));
    EXPECT_EQ(r.code, 0) << r.err;
    std::vector<std::pair<double, double>> a;  // (A_1, A_2) per point
    std::istringstream in(slurp(out + "/branches.csv"));
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      std::stringstream ss(line);
      std::string c[4];
      for (auto& x : c) std::getline(ss, x, ',');
      a.push_back({std::stod(c[2]), std::stod(c[3])});
    }
    return a;
  };
  const auto both = amplitudes("'metronomes.*.nu'");
  ASSERT_GT(both.size(), 5u);
  double spread = 0;
  for (const auto& [a1, a2] : both) {
    EXPECT_NEAR(a1, a2, 1e-9);
    spread = std::max(spread, std::abs(a1 - both.front().first));
  }
  EXPECT_GT(spread, 0.05);  // the amplitude moved with nu
  double asym = 0;
  for (const auto& [a1, a2] : amplitudes("metronomes.0.nu"))
    asym = std::max(asym, std::abs(a1 - a2));
  EXPECT_GT(asym, 1e-3);
}

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
      {"--param metronomes.*.bogus --from 1 --to 2", "bogus"},
      // the loader's own words for a value it refuses (not "makes the scaled nu infinite")
      {"--param platform.friction.mu --to -0.3",
       "--param platform.friction.mu=-0.3: platform.friction.mu = -0.3: must be >= 0"},
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
