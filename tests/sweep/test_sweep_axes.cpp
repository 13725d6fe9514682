// The richer axes of `metrosync sweep --vary` (issue 15): log spacing, wildcard keys
// (metronomes.*.nu), any number of axes (an N-D grid, maps per slice, --map), and the grid cap
// (--force). Bad input exits 2 with a message naming the fault and writes nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sim/analysis/sweep.h"
#include "tests/common/run_metrosync.h"
#include "tests/common/sweep_axis_values.h"

namespace metrosync {
namespace {

using testing_support::axisTexts;
using testing_support::axisValues;

namespace fs = std::filesystem;
using Result = testing_support::CommandResult;
using testing_support::shellQuote;
using testing_support::slurp;

std::string scratch(const std::string& name) {
  return testing_support::scratchDir("sweep_axes", name, true);
}

Result metrosync(const std::string& args) {
  return testing_support::runMetrosync(args);
}

using testing_support::csvRows;

std::string pairRig(const std::string& dir) {
  return metrosync::testing_support::writePairRig(dir, 30);
}

// ---- parsing ------------------------------------------------------------------------------------

TEST(SweepAxes, LogSpacingIsGeometricWithExactEnds) {
  const SweepAxis a = parseVary("platform.friction.mu=0.001:10:5:log");
  EXPECT_TRUE(a.log);
  EXPECT_EQ(axisTexts(a), (std::vector<std::string>{"0.001", "0.01", "0.1", "1", "10"}));
  // every value is the number its text denotes, and the ratios are equal (closed form
  // FROM * (TO/FROM)^(k/(COUNT-1)))
  const SweepAxis b = parseVary("k=2:50:7:log");
  ASSERT_EQ(axisValues(b).size(), 7u);
  EXPECT_EQ(axisValues(b).front(), 2.0);
  EXPECT_EQ(axisValues(b).back(), 50.0);
  for (size_t k = 0; k < axisValues(b).size(); ++k) {
    const double exact = 2.0 * std::pow(25.0, static_cast<double>(k) / 6.0);
    EXPECT_NEAR(axisValues(b)[k], exact, 1e-13 * exact) << k;
  }
  // open and log together: [FROM, TO) in log steps of (TO/FROM)^(1/COUNT)
  const SweepAxis c = parseVary("k=1:16:4:log:open");
  EXPECT_EQ(axisTexts(c), (std::vector<std::string>{"1", "2", "4", "8"}));
  EXPECT_EQ(axisTexts(parseVary("k=1:16:4:open:log")), axisTexts(c));
  // the manifest keeps the flag
  const SweepGrid g = SweepGrid::fromJson(SweepGrid({a}).toJson());
  EXPECT_TRUE(g.axes()[0].log);
  EXPECT_EQ(axisTexts(g.axes()[0]), axisTexts(a));
}

TEST(SweepAxes, BadAxesAreRejectedSayingWhy) {
  const std::vector<std::pair<const char*, const char*>> bad = {{"mu=0:1:3:log", "FROM > 0"},
                                                                {"mu=-1:-0.1:3:log", "FROM > 0"},
                                                                {"mu=1:0.1:3:log", "FROM <= TO"},
                                                                {"mu=1:2:3:log:log", "each once"},
                                                                {"mu=", "no values"},
                                                                {"mu=,", "not a number"}};
  for (const auto& [text, why] : bad) {
    try {
      parseVary(text);
      ADD_FAILURE() << "accepted " << text;
    } catch (const SweepInputError& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << text << ": " << e.what();
    }
  }
}

TEST(SweepAxes, AKeyGivenTwiceIsRefused) {
  // keys are kept as written (the command resolves them against the rig, docs/keys.md)
  EXPECT_EQ(parseVary("metronomes.*.nu=0.5:0.8:4").key, "metronomes.*.nu");
  EXPECT_THROW(
      SweepGrid({parseVary("metronomes.*.nu=0.5:0.8:4"), parseVary("metronomes.*.nu=1:2:2")}),
      SweepInputError);
  EXPECT_NO_THROW(
      SweepGrid({parseVary("metronomes.*.nu=0.5:0.8:4"), parseVary("metronomes.1.J=1:2:2")}));
}

TEST(SweepAxes, AnyNumberOfAxesUpToTheCapUnlessForced) {
  const SweepGrid g(
      {parseVary("a=0:1:2"), parseVary("b=0:2:3"), parseVary("c=1,5"), parseVary("d=0:1:2")});
  EXPECT_EQ(g.size(), 24);
  EXPECT_EQ(g.coordinates(23), (std::vector<long>{1, 2, 1, 1}));
  EXPECT_EQ(g.overrides(7), (std::vector<std::string>{"a=0", "b=1", "c=5", "d=1"}));
  EXPECT_EQ(g.overrides(13), (std::vector<std::string>{"a=1", "b=0", "c=1", "d=1"}));
  EXPECT_EQ(SweepGrid::fromJson(g.toJson()).size(), 24);
  // 10^7 points are allowed, one more axis value is not (without --force)
  EXPECT_EQ(SweepGrid({parseVary("a=0:1:10000"), parseVary("b=0:1:1000")}).size(), 10000000);
  EXPECT_THROW(SweepGrid({parseVary("a=0:1:10000"), parseVary("b=0:1:1001")}), SweepInputError);
  EXPECT_EQ(
      SweepGrid({parseVary("a=0:1:10000"), parseVary("b=0:1:1001")}, kMaxForcedGridPoints).size(),
      10010000);
}

TEST(SweepAxes, MapAxesAreChosenByKey) {
  const SweepGrid g({parseVary("a=0:1:2"), parseVary("b=0:1:1"), parseVary("c=0:1:3")});
  EXPECT_EQ(mapAxes(g, ""), (std::vector<size_t>{0, 2}));  // the first two of more than 1 value
  EXPECT_EQ(mapAxes(g, "c,a"), (std::vector<size_t>{2, 0}));
  EXPECT_THROW(mapAxes(g, "a,x"), SweepInputError);
  EXPECT_THROW(mapAxes(g, "a,a"), SweepInputError);
}

// ---- the command --------------------------------------------------------------------------------

TEST(SweepAxesCli, BadAxesExitTwoAndWriteNothing) {
  const std::string d = scratch("bad");
  const std::string rig = shellQuote(pairRig(d));
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"--vary platform.friction.mu=0:1:3:log", "FROM > 0"},
      {"--vary platform.friction.mu=-2:-1:3:log", "FROM > 0"},
      {"--vary platform.friction.mu=1:0.5:3:log", "FROM <= TO"},
      {"--vary platform.friction.mu=", "no values"},
      {"--vary 'metronomes.*.bogus=1:2:2'",
       "--vary metronomes.*.bogus=1:2:2: metronomes.*.bogus: unknown key"},
      {"--vary 'platform.*.mu=1:2:2'", "'*' stands for every element of a list"},
      {"--vary 'metronomes.*.nu=0.5:0.8:4' --vary metronomes.1.nu=1,2", "both set metronomes.1.nu"},
      {"--vary 'metronomes.*=1:2:2'", "metronomes.0 = 1: must be a map"},
      {"--vary a.b=0:1:10000 --vary c.d=0:1:1001", "--force"},
      {"--vary metronomes.0.nu=0.5:0.6:2 --map metronomes.0.nu,x.y", "--map"}};
  for (const auto& [args, why] : bad) {
    const std::string out = d + "/out";
    const Result r = metrosync("sweep " + rig + " " + args + " -q --out " + out);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(why), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
}

// Three axes, one a wildcard and one log-spaced: a row per point with one column per axis, in
// grid order, each row's values those of its point; the maps of each slice; --resume keeps all.
TEST(SweepAxesCli, ThreeAxesWriteTheRightRows) {
  const std::string d = scratch("nd");
  const std::string rig = shellQuote(pairRig(d));
  const std::string grid =
      " --vary 'metronomes.*.nu=0.6,0.7' --vary platform.friction.mu=0.01:1:3:log"
      " --vary metronomes.0.start.phi=0:pi:2 --map platform.friction.mu,metronomes.0.start.phi";
  const Result r = metrosync("sweep " + rig + grid + " -q --jobs 2 --out " + d + "/nd");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = csvRows(d + "/nd/regimes.csv");
  ASSERT_EQ(rows.size(), 13u);
  EXPECT_EQ(rows[0][0], "metronomes.*.nu");
  EXPECT_EQ(rows[0][1], "platform.friction.mu");
  EXPECT_EQ(rows[0][2], "metronomes.0.start.phi");
  EXPECT_EQ(rows[0][3], "regime");
  const std::vector<std::string> nu = {"0.6", "0.7"}, mu = {"0.01", "0.1", "1"},
                                 phi = {"0", "3.14159265358979"};
  for (long g = 0; g < 12; ++g) {
    const auto& row = rows[g + 1];
    EXPECT_EQ(row[0], nu[g / 6]) << g;
    EXPECT_EQ(row[1], mu[(g / 2) % 3]) << g;
    EXPECT_EQ(row[2], phi[g % 2]) << g;
    EXPECT_EQ(row[12], std::to_string(g));  // index, after 2 A and 1 psi
    EXPECT_EQ(row[11], "1") << g;           // complete
  }
  // the wildcard set both metronomes: the rows at nu = 0.7 are those of a sweep with both set
  // by --set (identical metronomes started in phase stay in phase with equal amplitudes)
  EXPECT_EQ(rows[1][3], "in-phase");
  EXPECT_NEAR(std::stod(rows[1][4]), std::stod(rows[1][5]), 1e-9);
  EXPECT_NE(rows[7][4], rows[1][4]);  // nu changed the amplitudes
  const Result both = metrosync("sweep " + rig +
                                " --set metronomes.0.nu=0.7 --set metronomes.1.nu=0.7"
                                " --vary platform.friction.mu=0.01:1:3:log"
                                " --vary metronomes.0.start.phi=0:pi:2 -q --no-plot --out " +
                                d + "/both");
  ASSERT_EQ(both.code, 0) << both.err;
  const auto ref = csvRows(d + "/both/regimes.csv");
  ASSERT_EQ(ref.size(), 7u);
  for (size_t k = 1; k < ref.size(); ++k)
    for (size_t c = 0; c < 6; ++c)  // mu, phi, regime, A_1, A_2, psi_2
      EXPECT_EQ(rows[6 + k][1 + c], ref[k][c]) << k << " " << c;
  // maps: one set per value of the axis not drawn
  for (const char* f : {"regimes--metronomes.all.nu=0.6.png", "regimes--metronomes.all.nu=0.7.png"})
    EXPECT_TRUE(fs::exists(d + "/nd/" + f)) << f;
  EXPECT_FALSE(fs::exists(d + "/nd/regimes.png"));
  // --resume of a complete N-D sweep runs nothing and keeps the file
  const std::string before = slurp(d + "/nd/regimes.csv");
  const Result again = metrosync("sweep " + rig + grid + " --resume --jobs 1 --out " + d + "/nd");
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_NE(again.out.find("(0 now, 12 before)"), std::string::npos) << again.out;
  EXPECT_EQ(slurp(d + "/nd/regimes.csv"), before);
}

}  // namespace
}  // namespace metrosync
