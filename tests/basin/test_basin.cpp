// Basin stability (`metrosync basin`, sim/analysis/basin.h): the draws (uniform, on the circle for
// angles, a function of (seed, sample) only), the Wilson interval against textbook values, and
// the command on cases with a known answer: a single metronome started above its escapement
// angle always keeps swinging (the limit cycle attracts every such start), below it always dies;
// two identical metronomes drawn from one distribution are as likely to lose the first as the
// second (exchange symmetry). The same basin.csv for --jobs 1 and 2.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/constants.h"
#include "sim/analysis/basin.h"
#include "sim/analysis/sweep.h"
#include "tests/common/run_metrosync.h"

namespace metrosync {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Result = testing_support::CommandResult;
using testing_support::shellQuote;
using testing_support::slurp;

constexpr double kThetaC = 0.9019;  // the rigs' escapement angle (scaled)

std::string scratch(const std::string& name) {
  return testing_support::scratchDir("basin", name, true);
}

Result metrosync(const std::string& args) {
  return testing_support::runMetrosync(args);
}

using testing_support::csvRows;

// N identical metronomes of the paper's experiment (scaled), a short run.
std::string rig(const std::string& dir, int n) {
  const std::string path = dir + "/rig" + std::to_string(n) + ".yaml";
  std::ofstream f(path);
  f << "units: scaled\nname: rig" << n << "\nepsilon: 0.07319\n"
    << "platform:\n  friction: {law: coulomb, mu: 0.03283}\nmetronomes:\n";
  for (int i = 0; i < n; ++i)
    f << "  - {nu: 0.6544, J: 3.138, theta_c: " << kThetaC << ", start: {A: 2.902, phi: 0}}\n";
  f << "simulation:\n  tau: 30\n";
  return shellQuote(path);
}

// ---- the draws and the interval -----------------------------------------------------------------

TEST(BasinDraw, UniformInRangeAndAFunctionOfSeedAndSampleOnly) {
  const RandomKey a = parseRandom("metronomes.1.start.A=1:4", false);
  EXPECT_FALSE(a.angle);
  const long n = 20000;
  double sum = 0.0;
  long below_2 = 0;
  for (long k = 0; k < n; ++k) {
    const double v = drawValue(a, 42, k, 0);
    ASSERT_GE(v, 1.0);
    ASSERT_LT(v, 4.0);
    sum += v;
    below_2 += v < 2.0;
  }
  // mean 2.5, sd of the mean sqrt(0.75 / n) = 0.006; P(v < 2) = 1/3, sd 0.0033
  EXPECT_NEAR(sum / n, 2.5, 0.03);
  EXPECT_NEAR(static_cast<double>(below_2) / n, 1.0 / 3.0, 0.017);
  // the same (seed, sample) gives the same value whatever was drawn before; other seeds differ
  EXPECT_EQ(drawValue(a, 42, 1234, 0), drawValue(a, 42, 1234, 0));
  EXPECT_NE(drawValue(a, 42, 1234, 0), drawValue(a, 43, 1234, 0));
  // two keys of one sample are not the same draw, nor correlated
  double cov = 0.0;
  for (long k = 0; k < n; ++k)
    cov += (basinUniform(42, k, 0) - 0.5) * (basinUniform(42, k, 1) - 0.5);
  EXPECT_NEAR(cov / n * 12.0, 0.0, 0.05);  // correlation coefficient, sd 0.007
}

TEST(BasinDraw, AnglesAreDrawnOnTheCircleAndWrapped) {
  const RandomKey whole = parseRandom("metronomes.0.start.phi=-pi:pi", true);
  EXPECT_TRUE(whole.angle);
  // a pendulum's start angle is not a phase: drawn as given, never wrapped
  EXPECT_TRUE(isPhaseName("phi") && isPhaseName("psi"));
  EXPECT_FALSE(isPhaseName("angle"));
  EXPECT_FALSE(parseRandom("metronomes.0.start.angle=-0.8:0.8", false).angle);
  EXPECT_LT(drawValue(parseRandom("metronomes.0.start.angle=-0.8:-0.7", false), 1, 0, 0), 0.0);
  const RandomKey arc = parseRandom("metronomes.0.start.phi=5.5:0.5", true);  // through 2 pi
  long near_zero = 0;
  for (long k = 0; k < 5000; ++k) {
    const double w = drawValue(whole, 3, k, 0);
    ASSERT_GE(w, 0.0);
    ASSERT_LT(w, 2 * kPi);
    const double v = drawValue(arc, 3, k, 0);
    ASSERT_TRUE((v >= 5.5 && v < 2 * kPi) || (v >= 0.0 && v < 0.5)) << v;
    near_zero += v < 0.5;
  }
  // the arc is 2 pi - 5.5 + 0.5 = 1.2832 long; 0.5 of it past zero
  EXPECT_NEAR(near_zero / 5000.0, 0.5 / (2 * kPi - 5.0), 0.03);
  for (const char* bad : {"x", "x=1", "x=1:2:3", "x=2:1", "x=1:1", "x=a:2", "=0:1"})
    EXPECT_THROW(parseRandom(bad, false), SweepInputError) << bad;
  EXPECT_THROW(parseRandom("metronomes.0.start.phi=1:1", true), SweepInputError);
}

TEST(BasinWilson, MatchesTheClosedForm) {
  // textbook values (Wilson 1927; e.g. Newcombe, Stat. Med. 17, 857 (1998), table I: 0/10 and
  // 5/10 -> [0, 0.2775] and [0.2366, 0.7634])
  const WilsonInterval zero = wilsonInterval(0, 10);
  EXPECT_EQ(zero.lo, 0.0);
  EXPECT_NEAR(zero.hi, 0.2775, 5e-5);
  const WilsonInterval half = wilsonInterval(5, 10);
  EXPECT_NEAR(half.lo, 0.2366, 5e-5);
  EXPECT_NEAR(half.hi, 0.7634, 5e-5);
  // all successes: [n / (n + z^2), 1]
  const double z = 1.959963984540054;
  const WilsonInterval all = wilsonInterval(100, 100);
  EXPECT_NEAR(all.lo, 100.0 / (100.0 + z * z), 1e-12);
  EXPECT_EQ(all.hi, 1.0);
  // fractions: most frequent first, counts and intervals per regime
  const auto f = regimeFractions({"a", "b", "b", "c", "b"});
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f[0].regime, "b");
  EXPECT_EQ(f[0].count, 3);
  EXPECT_DOUBLE_EQ(f[0].fraction, 0.6);
  EXPECT_DOUBLE_EQ(f[0].ci.lo, wilsonInterval(3, 5).lo);
}

// ---- the command --------------------------------------------------------------------------------

TEST(BasinCli, SameBasinCsvForOneAndTwoJobs) {
  const std::string d = scratch("jobs");
  const std::string args = "basin " + rig(d, 2) +
                           " --random metronomes.0.start.phi=0:2pi --random "
                           "metronomes.1.start.A=1:4 --samples 40 --seed 9 -q --no-plot";
  ASSERT_EQ(metrosync(args + " --jobs 1 --out " + d + "/j1").code, 0);
  const Result two = metrosync(args + " --jobs 2 --out " + d + "/j2");
  ASSERT_EQ(two.code, 0) << two.err;
  const std::string a = slurp(d + "/j1/basin.csv");
  EXPECT_EQ(a, slurp(d + "/j2/basin.csv"));
  const auto rows = csvRows(d + "/j1/basin.csv");
  ASSERT_EQ(rows.size(), 41u);
  EXPECT_EQ(rows[0][0], "sample");
  EXPECT_EQ(rows[0][1], "metronomes.0.start.phi");
  EXPECT_EQ(rows[0][3], "regime");
  // row k holds sample k's draws for seed 9
  const std::vector<RandomKey> keys = {parseRandom("metronomes.0.start.phi=0:2pi", true),
                                       parseRandom("metronomes.1.start.A=1:4", false)};
  for (long k = 0; k < 40; ++k) {
    const std::vector<double> v = drawSample(keys, 9, k);
    EXPECT_EQ(rows[k + 1][0], std::to_string(k));
    EXPECT_EQ(rows[k + 1][1], sweepValueText(v[0]));
    EXPECT_EQ(rows[k + 1][2], sweepValueText(v[1]));
  }
  // the fractions in basin.json add up to the samples and match the rows
  const json j = json::parse(slurp(d + "/j1/basin.json"));
  long total = 0;
  for (const auto& f : j["fractions"]) {
    long rows_of = 0;
    for (size_t k = 1; k < rows.size(); ++k) rows_of += rows[k][3] == f["regime"];
    EXPECT_EQ(f["count"].get<long>(), rows_of) << f["regime"];
    total += f["count"].get<long>();
  }
  EXPECT_EQ(total, 40);
  EXPECT_EQ(j["seed"], 9);
  // another seed draws other starts
  ASSERT_EQ(metrosync("basin " + rig(d, 2) +
                      " --random metronomes.0.start.phi=0:2pi --random metronomes.1.start.A=1:4"
                      " --samples 40 --seed 10 -q --no-plot --out " +
                      d + "/s10")
                .code,
            0);
  EXPECT_NE(slurp(d + "/s10/basin.csv"), a);
}

// One metronome: above its escapement angle every start reaches the limit cycle (alive), below it
// every start decays (death): fraction 1 with the interval [S / (S + z^2), 1].
TEST(BasinCli, AGloballyAttractingStateHasFractionOne) {
  const std::string d = scratch("global");
  const Result up = metrosync("basin " + rig(d, 1) +
                              " --random metronomes.0.start.A=0.95:4 --random "
                              "metronomes.0.start.phi=0:2pi --samples 60 --out " +
                              d + "/up");
  ASSERT_EQ(up.code, 0) << up.err;
  const json j = json::parse(slurp(d + "/up/basin.json"));
  ASSERT_EQ(j["fractions"].size(), 1u) << j["fractions"].dump();
  EXPECT_EQ(j["fractions"][0]["regime"], "alive");
  EXPECT_EQ(j["fractions"][0]["fraction"], 1.0);
  const double z = 1.959963984540054;
  EXPECT_NEAR(j["fractions"][0]["ci95"][0].get<double>(), 60.0 / (60.0 + z * z), 1e-12);
  EXPECT_NE(up.out.find("alive"), std::string::npos) << up.out;
  EXPECT_NE(up.out.find("[0.9398, 1.0000]"), std::string::npos) << up.out;
  EXPECT_TRUE(fs::exists(d + "/up/basin.png"));  // two keys: a map
  const Result down =
      metrosync("basin " + rig(d, 1) +
                " --random metronomes.0.start.A=0.01:0.89 --samples 30 -q --out " + d + "/down");
  ASSERT_EQ(down.code, 0) << down.err;
  const json k = json::parse(slurp(d + "/down/basin.json"));
  ASSERT_EQ(k["fractions"].size(), 1u);
  EXPECT_EQ(k["fractions"][0]["regime"], "death");
  EXPECT_FALSE(fs::exists(d + "/down/basin.png"));  // one key: no map
}

// Two identical metronomes whose starts are drawn from one distribution: exchanging them maps the
// draws onto themselves, so "the first dies" and "the second dies" are equally likely; the pooled
// estimate lies in both Wilson intervals. At mu = 0.55 over tau = 300 suppression is common (71 of
// 400 samples with seed 1); the regime rules judge a metronome still dying at the end unsettled,
// so short runs at low friction have too few suppressed samples to say anything.
TEST(BasinCli, ExchangeSymmetryGivesEqualFractions) {
  const std::string d = scratch("symmetric");
  const Result r = metrosync("basin " + rig(d, 2) +
                             " --random metronomes.0.start.A=0.5:4 --random "
                             "metronomes.1.start.A=0.5:4 --random metronomes.0.start.phi=0:2pi "
                             "--random metronomes.1.start.phi=0:2pi --samples 400 --seed 1 -q "
                             "--no-plot --set platform.friction.mu=0.55 --set simulation.tau=300 "
                             "--out " +
                             d + "/b");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = csvRows(d + "/b/basin.csv");
  ASSERT_EQ(rows.size(), 401u);
  long first = 0, second = 0;
  for (size_t k = 1; k < rows.size(); ++k) {
    if (rows[k][5] != "suppression") continue;
    const double a1 = std::stod(rows[k][6]), a2 = std::stod(rows[k][7]);
    first += a1 < kThetaC && a2 >= kThetaC;
    second += a2 < kThetaC && a1 >= kThetaC;
  }
  ASSERT_GT(first + second, 20);  // enough suppressed samples to say something
  const double pooled = (first + second) / 800.0;
  for (long k : {first, second}) {
    const WilsonInterval ci = wilsonInterval(k, 400);
    EXPECT_LE(ci.lo, pooled) << first << " / " << second;
    EXPECT_GE(ci.hi, pooled) << first << " / " << second;
  }
}

TEST(BasinCli, BadInputExitsTwoAndWritesNothing) {
  const std::string d = scratch("bad");
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"--random metronomes.0.start.A --samples 5", "KEY=FROM:TO"},
      {"--random metronomes.0.start.A=3:1 --samples 5", "FROM must be below TO"},
      {"--random metronomes.0.start.A=1:3 --samples 0", "--samples"},
      {"--random metronomes.0.start.bogus=1:3 --samples 5", "unknown key"},
      {"--random metronomes.0.start.A=1:3 --random metronomes.0.start.A=1:2 --samples 5", "twice"}};
  for (const auto& [args, why] : bad) {
    const Result r = metrosync("basin " + rig(d, 2) + " " + args + " -q --out " + d + "/out");
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(why), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(d + "/out")) << args;
  }
}

}  // namespace
}  // namespace metrosync

namespace metrosync {
namespace {

// sweep --basin-samples: each point's in_phase_fraction is what `metrosync basin` reports for the
// same draws at that point (two commands, one answer); --resume checks the draws.
TEST(BasinSweep, InPhaseFractionPerPointEqualsTheBasinCommand) {
  const std::string d = scratch("sweep");
  const std::string r = rig(d, 2);
  const std::string draws =
      " --random metronomes.0.start.phi=0:2pi --random metronomes.1.start.A=1:4 --seed 5";
  const std::string cmd = "sweep " + r + " --vary platform.friction.mu=0,0.3" +
                          " --basin-samples 16" + draws + " -q --no-plot --out " + d + "/sw";
  const Result s = metrosync(cmd);
  ASSERT_EQ(s.code, 0) << s.err;
  const auto rows = csvRows(d + "/sw/regimes.csv");
  ASSERT_EQ(rows.size(), 3u);
  ASSERT_EQ(rows[0][9], "in_phase_fraction");
  for (size_t k = 1; k < rows.size(); ++k) {
    const Result b =
        metrosync("basin " + r + " --set platform.friction.mu=" + rows[k][0] + " --samples 16" +
                  draws + " -q --no-plot --out " + d + "/b" + std::to_string(k));
    ASSERT_EQ(b.code, 0) << b.err;
    double in_phase = 0.0;
    const json j = json::parse(slurp(d + "/b" + std::to_string(k) + "/basin.json"));
    for (const auto& f : j["fractions"])
      if (f["regime"] == "in-phase") in_phase = f["fraction"].get<double>();
    EXPECT_DOUBLE_EQ(std::stod(rows[k][9]), in_phase) << rows[k][0];
  }
  // resuming with the same draws keeps the rows; other draws are another sweep (exit 2)
  const std::string before = slurp(d + "/sw/regimes.csv");
  ASSERT_EQ(metrosync(cmd + " --resume").code, 0);
  EXPECT_EQ(slurp(d + "/sw/regimes.csv"), before);
  const Result other = metrosync("sweep " + r + " --vary platform.friction.mu=0,0.3" +
                                 " --basin-samples 16 --random metronomes.0.start.phi=0:2pi "
                                 "--seed 6 -q --no-plot --resume --out " +
                                 d + "/sw");
  EXPECT_EQ(other.code, 2) << other.err;
  EXPECT_NE(other.err.find("--basin-samples"), std::string::npos) << other.err;
  // --basin-samples without --random, and a --random key that is also a --vary key: exit 2
  EXPECT_EQ(metrosync("sweep " + r +
                      " --vary platform.friction.mu=0,0.3 --basin-samples 4 -q "
                      "--out " +
                      d + "/bad1")
                .code,
            2);
  EXPECT_EQ(metrosync("sweep " + r +
                      " --vary platform.friction.mu=0,0.3 --basin-samples 4 "
                      "--random platform.friction.mu=0:1 -q --out " +
                      d + "/bad2")
                .code,
            2);
  EXPECT_FALSE(fs::exists(d + "/bad1"));
  EXPECT_FALSE(fs::exists(d + "/bad2"));
}

}  // namespace
}  // namespace metrosync
