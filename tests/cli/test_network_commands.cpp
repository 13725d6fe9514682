// Every command takes a network of platforms or refuses it with exit 2 and a reason (issue 24):
// basin and sweep with coupling keys (a row is what `run` says of the same values), fit, compare,
// continue and scale refuse, and so does the slow flow in run, sweep and basin.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/common/run_metrosync.h"

namespace metrosync {
namespace {

using testing_support::csvRows;
using testing_support::runMetrosync;
using testing_support::scratchDir;
using testing_support::shellQuote;
using testing_support::slurp;

const std::string kRig = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/two-boards-rollers.yaml";

// basin --random couplings.0.k: each sample's row is the final state `run` reports for its k
TEST(NetworkCommands, BasinOverACouplingIsWhatRunSaysOfEachSample) {
  const std::string d = scratchDir("netcmd", "basin", true);
  const auto b = runMetrosync("basin " + shellQuote(kRig) +
                              " --random couplings.0.k=1:5 --samples 2 --seed 3 -q "
                              "--set simulation.duration=2 --out " +
                              shellQuote(d + "/basin"));
  ASSERT_EQ(b.code, 0) << b.err;
  const auto t = csvRows(d + "/basin/basin.csv");
  ASSERT_EQ(t.size(), 3u);
  ASSERT_EQ(t[0][1], "couplings.0.k");
  for (std::size_t row = 1; row < t.size(); ++row) {
    const double k = std::stod(t[row][1]);
    EXPECT_TRUE(k >= 1 && k <= 5) << k;
    const std::string out = d + "/run" + std::to_string(row);
    const auto r =
        runMetrosync("run " + shellQuote(kRig) + " -q --no-plot --set couplings.0.k=" + t[row][1] +
                     " --set simulation.duration=2 --out " + shellQuote(out));
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json s = nlohmann::json::parse(slurp(out + "/summary.json"));
    EXPECT_EQ(s["regime"].get<std::string>(), t[row][2]) << "k = " << k;
    ASSERT_EQ(s["final"]["A"].size(), 4u);
    // the CSV's k has 15 digits: the two runs differ by that rounding only
    for (int i = 0; i < 4; ++i)
      EXPECT_NEAR(s["final"]["A"][i].get<double>(), std::stod(t[row][3 + i]), 1e-8) << i;
  }
}

// `couplings.*.k` sets every coupling: on a rig with one, the same table as `couplings.0.k`
TEST(NetworkCommands, SweepOverEveryCouplingIsTheSweepOverTheOne) {
  const std::string d = scratchDir("netcmd", "sweep", true);
  std::vector<std::vector<std::vector<std::string>>> tables;
  for (const std::string key : {"couplings.*.k", "couplings.0.k"}) {
    const std::string out = d + "/" + std::to_string(tables.size());
    const auto r =
        runMetrosync("sweep " + shellQuote(kRig) + " --vary '" + key +
                     "=1,50' --set simulation.duration=2 --jobs 1 -q --out " + shellQuote(out));
    ASSERT_EQ(r.code, 0) << r.err;
    tables.push_back(csvRows(out + "/regimes.csv"));
    EXPECT_EQ(tables.back()[0][0], key);
  }
  ASSERT_EQ(tables[0].size(), 3u);
  for (std::size_t row = 1; row < 3; ++row)  // every column but the timing-free identical ones
    EXPECT_EQ(tables[0][row], tables[1][row]) << row;
  EXPECT_NE(tables[0][1][3], tables[0][2][3]);  // and k changed the outcome
}

TEST(NetworkCommands, SingleRigCommandsRefuseANetworkWithExitTwo) {
  const std::string d = scratchDir("netcmd", "refuse", true);
  std::ofstream(d + "/data.csv") << "t,theta_1\n0,0.1\n0.1,0.05\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"fit " + shellQuote(kRig) + " " + shellQuote(d + "/data.csv") + " --free couplings.0.k",
       "a network of 2 platforms"},
      {"compare " + shellQuote(kRig), "a network of 2 platforms"},
      {"continue " + shellQuote(kRig) + " --param couplings.0.k --to 5",
       "a network of 2 platforms"},
      {"continue " + shellQuote(kRig) + " --model full --param couplings.0.k --to 5",
       "a network of 2 platforms"},
      {"run " + shellQuote(kRig) + " --model slow", "the slow flow is single-platform"},
      {"sweep " + shellQuote(kRig) + " --model slow --vary couplings.0.k=1:5:2",
       "the slow flow is single-platform"},
      {"basin " + shellQuote(kRig) + " --model slow --random couplings.0.k=1:5 --samples 2",
       "the slow flow is single-platform"},
  };
  int k = 0;
  for (const auto& [cmd, reason] : cases) {
    const std::string out = d + "/out" + std::to_string(k++);
    const auto r = runMetrosync(cmd + " -q --out " + shellQuote(out));
    EXPECT_EQ(r.code, 2) << cmd << "\n" << r.err;
    EXPECT_NE(r.err.find(reason), std::string::npos) << cmd << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << cmd;
  }
  const auto s = runMetrosync("scale " + shellQuote(kRig));
  EXPECT_EQ(s.code, 2);
  EXPECT_NE(s.err.find("a network of 2 platforms"), std::string::npos) << s.err;
}

}  // namespace
}  // namespace metrosync
