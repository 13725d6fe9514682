// The pieces of a sweep without the command line: --vary and --shard syntax, the grid, the
// regimes.csv rows (and a file cut by kill -9), the order parameter r and the cluster names of
// N >= 3 (sim/analysis/regime.h) on synthetic envelopes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <set>
#include <sstream>

#include "base/constants.h"
#include "models/scaling.h"
#include "sim/analysis/regime.h"
#include "sim/analysis/sweep.h"
#include "sim/engines/slow_flow/slow_flow_engine.h"
#include "sim/record/envelope.h"
#include "sim/record/envelope_csv.h"
#include "tests/common/sweep_axis_values.h"
#include "tools/report/sweep_files.h"
#include "tools/report/sweep_maps.h"

namespace metrosync {
namespace {

using testing_support::axisTexts;
using testing_support::axisValues;

namespace fs = std::filesystem;

std::string scratchFile(const std::string& name) {
  return ::testing::TempDir() + "/metrosync_sweep_" + name + "_" + std::to_string(::getpid());
}

// ---- --vary, --shard, the grid
// -------------------------------------------------------------------

TEST(SweepVary, ParsesBothEndsIncludedAndTheOpenForm) {
  const SweepAxis a = parseVary("platform.friction.mu=0:1:5");
  EXPECT_EQ(a.key, "platform.friction.mu");
  ASSERT_EQ(a.count, 5);
  EXPECT_EQ(axisTexts(a), (std::vector<std::string>{"0", "0.25", "0.5", "0.75", "1"}));
  // [0, 2 pi): TO left out, values 2 pi k / 4, written so that they read back exactly
  const SweepAxis b = parseVary("metronomes.0.start.phi=0:2pi:4:open");
  ASSERT_EQ(axisValues(b).size(), 4u);
  EXPECT_TRUE(b.open);
  EXPECT_EQ(axisValues(b)[0], 0.0);
  EXPECT_NEAR(axisValues(b)[2], kPi, 1e-14);
  EXPECT_NEAR(axisValues(b)[3], 1.5 * kPi, 1e-14);
  EXPECT_EQ(axisTexts(parseVary("x=0:8e-4:33"))[3], "7.5e-05");  // not 7.500000000000001e-05
  for (size_t k = 0; k < axisTexts(b).size(); ++k)
    EXPECT_EQ(std::strtod(axisTexts(b)[k].c_str(), nullptr), axisValues(b)[k]) << axisTexts(b)[k];
  // one value; negative and decreasing ranges
  EXPECT_EQ(axisTexts(parseVary("metronomes.1.alpha=0.3:9:1")), (std::vector<std::string>{"0.3"}));
  EXPECT_EQ(axisTexts(parseVary("k=1:-1:3")), (std::vector<std::string>{"1", "0", "-1"}));
}

TEST(SweepVary, ReadsAListOfValuesAsGiven) {
  // the paper's three frictions, in the order given, and pi as in a range
  const SweepAxis a = parseVary("platform.friction.mu=0.4,0.2,0.3");
  EXPECT_EQ(a.count, 3);
  EXPECT_EQ(axisTexts(a), (std::vector<std::string>{"0.4", "0.2", "0.3"}));
  EXPECT_EQ(axisValues(a), (std::vector<double>{0.4, 0.2, 0.3}));
  EXPECT_EQ(axisValues(parseVary("x=0,pi"))[1], std::strtod(sweepValueText(kPi).c_str(), nullptr));
  // the manifest keeps a list axis's values
  const SweepGrid g = SweepGrid::fromJson(SweepGrid({a}).toJson());
  EXPECT_EQ(axisTexts(g.axes()[0]), axisTexts(a));
  for (const char* bad : {"x=0.3,", "x=,1", "x=1,a", "x=1,2:3"})
    EXPECT_THROW(parseVary(bad), SweepInputError) << bad;
}

TEST(SweepVary, ReadsMultiplesOfPi) {
  EXPECT_EQ(parseSweepNumber("pi"), kPi);
  EXPECT_EQ(parseSweepNumber("2pi"), 2 * kPi);
  EXPECT_EQ(parseSweepNumber("2*pi"), 2 * kPi);
  EXPECT_EQ(parseSweepNumber("-pi/2"), -kPi / 2);
  EXPECT_EQ(parseSweepNumber(" 1.5e-3 "), 1.5e-3);
  for (const char* bad : {"", "pie", "2pi2", "pi/0", "x", "nan", "inf", "1e999", "0x10", "pipi"})
    EXPECT_THROW(parseSweepNumber(bad), SweepInputError) << bad;
}

TEST(SweepVary, RejectsBadSyntaxSayingWhatIsExpected) {
  for (const char* bad :
       {"platform.friction.mu", "platform.friction.mu=0:1", "=0:1:3", "platform.friction.mu=0:1:0",
        "platform.friction.mu=0:1:2.5", "platform.friction.mu=0:1:-3", "platform.friction.mu=a:1:3",
        "platform.friction.mu=0:1:3:closed", "platform.friction.mu=0:1:3:open:x"}) {
    try {
      parseVary(bad);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const SweepInputError& e) {
      EXPECT_NE(std::string(e.what()).find("--vary"), std::string::npos) << e.what();
    }
  }
}

TEST(SweepGrid, FirstAxisIsTheOuterOneAndOverridesNameThePoint) {
  const SweepGrid grid({parseVary("a=0:2:3"), parseVary("b.c=10:40:4")});
  EXPECT_EQ(grid.size(), 12);
  EXPECT_EQ(grid.coordinates(0), (std::vector<long>{0, 0}));
  EXPECT_EQ(grid.coordinates(5), (std::vector<long>{1, 1}));
  EXPECT_EQ(grid.coordinates(11), (std::vector<long>{2, 3}));
  EXPECT_EQ(grid.overrides(7), (std::vector<std::string>{"a=1", "b.c=40"}));
  // round trip through sweep.json
  const SweepGrid back = SweepGrid::fromJson(grid.toJson());
  EXPECT_EQ(back.size(), 12);
  EXPECT_EQ(axisTexts(back.axes()[1]), axisTexts(grid.axes()[1]));
  EXPECT_THROW(SweepGrid(std::vector<SweepAxis>{}), SweepInputError);
  EXPECT_THROW(SweepGrid({parseVary("a=0:1:2"), parseVary("a=0:1:3")}), SweepInputError);
  // a third axis is an N-D grid (tests/sweep/test_sweep_axes.cpp); a key twice is still an error
  EXPECT_THROW(SweepGrid({parseVary("a=0:1:2"), parseVary("b=0:1:2"), parseVary("a=0:1:2")}),
               SweepInputError);
}

TEST(SweepShard, SlicesAreDisjointAndCoverTheGrid) {
  const SweepGrid grid({parseVary("a=0:1:7"), parseVary("b=0:1:5")});
  std::multiset<long> seen;
  for (int k = 1; k <= 4; ++k)
    for (long g : shardIndices(grid, parseShard(std::to_string(k) + "/4"))) {
      EXPECT_EQ(g % 4, k - 1);
      seen.insert(g);
    }
  ASSERT_EQ(seen.size(), 35u);
  for (long g = 0; g < 35; ++g) EXPECT_EQ(seen.count(g), 1u) << g;
  for (const char* bad : {"0/3", "4/3", "1/0", "1", "a/b", "1/3/3", "-1/3", ""})
    EXPECT_THROW(parseShard(bad), SweepInputError) << bad;
}

// ---- regimes.csv
// ----------------------------------------------------------------------------------

SweepPoint samplePoint(long index) {
  SweepPoint p;
  p.index = index;
  p.regime = "suppressed:1;clusters:2+1";
  p.A = {2.5, 0.3, 2.5, 2.4};
  p.psi = {3.1, 0.01, 6.2};
  p.r = 0.5;
  p.s = 1.75;  // (no value, NaN, is an empty cell: a Coulomb platform at mu > 0 has one)
  p.clusters = "2+1";
  p.tau = 305.6;
  return p;
}

TEST(RegimesCsv, RowsRoundTripWithTheirFailureMessage) {
  const SweepGrid grid(
      {parseVary("metronomes.0.start.phi=0:2pi:4:open"), parseVary("platform.friction.mu=0:1:3")});
  EXPECT_EQ(regimesHeader(grid, 2),
            "metronomes.0.start.phi,platform.friction.mu,regime,A_1,A_2,psi_2,r,s,clusters,tau,"
            "complete,index,message");
  SweepPoint p = samplePoint(7);
  const std::string line = formatRegimesRow(grid, p);
  EXPECT_EQ(line.rfind("3.14159265358979,0.5,", 0), 0u) << line;  // point 7: phi = pi, mu = 0.5
  const SweepPoint q = parseRegimesRow(grid, 4, line);
  EXPECT_EQ(q.index, 7);
  EXPECT_EQ(q.regime, p.regime);
  EXPECT_EQ(q.A, p.A);
  EXPECT_EQ(q.psi, p.psi);
  EXPECT_EQ(q.clusters, "2+1");
  EXPECT_EQ(q.s, p.s);
  EXPECT_TRUE(q.complete);
  // a failure: message with a comma and quotes stays one cell, NaNs for what is not known
  SweepPoint f;
  f.index = 2;
  f.regime = "failed";
  f.complete = false;
  f.A = {NAN, NAN};
  f.psi = {NAN};
  f.message = "stopped at t = 3: event storm (50 switches, \"chattering\")\nat the escapement";
  const std::string fl = formatRegimesRow(grid, f);
  EXPECT_EQ(fl.find('\n'), std::string::npos);
  const SweepPoint g = parseRegimesRow(grid, 2, fl);
  EXPECT_FALSE(g.complete);
  EXPECT_EQ(g.regime, "failed");
  EXPECT_TRUE(std::isnan(g.A[0]));
  EXPECT_EQ(g.message,
            "stopped at t = 3: event storm (50 switches, \"chattering\") at the escapement");
  // a row whose key values are not its point's, or whose index is off the grid
  std::string moved = formatRegimesRow(grid, samplePoint(7));
  moved.replace(0, moved.find(','), "0");
  EXPECT_THROW(parseRegimesRow(grid, 4, moved), SweepInputError);
  EXPECT_THROW(parseRegimesRow(grid, 4, formatRegimesRow(grid, samplePoint(7)) + ",x"),
               SweepInputError);
}

TEST(RegimesCsv, ACutLastLineIsDroppedAndTheRestKept) {
  const SweepGrid grid({parseVary("platform.friction.mu=0:1:11")});
  const std::string path = scratchFile("cut.csv");
  std::string text = regimesHeader(grid, 4) + "\n";
  for (long g : {3L, 0L, 5L}) text += formatRegimesRow(grid, samplePoint(g)) + "\n";
  const size_t whole = text.size();
  const std::string next = formatRegimesRow(grid, samplePoint(8));
  text += next.substr(0, next.size() / 2);  // kill -9 in the middle of a write
  std::ofstream(path, std::ios::binary) << text;
  const RegimesTable t = readRegimesCsv(path, grid, 4);
  EXPECT_EQ(t.partial_lines, 1);
  EXPECT_EQ(t.complete_bytes, whole);
  EXPECT_EQ(t.lines.size(), 3u);
  EXPECT_TRUE(t.lines.count(5));
  EXPECT_FALSE(t.lines.count(8));
  // appending after cutting it leaves whole lines only
  {
    RegimesAppender app(path, regimesHeader(grid, 4), false, t.complete_bytes);
    app.append(next);
  }
  const RegimesTable u = readRegimesCsv(path, grid, 4);
  EXPECT_EQ(u.partial_lines, 0);
  EXPECT_EQ(u.lines.size(), 4u);
  EXPECT_EQ(u.lines.at(8), next);
  // another sweep's file is refused
  const SweepGrid other({parseVary("platform.friction.mu=0:1:12")});
  EXPECT_NO_THROW(readRegimesCsv(path, other, 4));  // same header: rows checked one by one
  EXPECT_THROW(readRegimesCsv(path, SweepGrid({parseVary("metronomes.1.alpha=0:1:11")}), 4),
               SweepInputError);
  fs::remove(path);
}

TEST(SweepManifest, DifferencesAreNamed) {
  SweepManifest a;
  a.model = "slow";
  a.rig_text = "units: scaled\n";
  a.metronomes = 2;
  a.grid = SweepGrid({parseVary("platform.friction.mu=0:1:11")});
  SweepManifest b = SweepManifest::fromJson(a.toJson());
  EXPECT_EQ(sweepDifference(a, b), "");
  b.model = "full";
  EXPECT_NE(sweepDifference(a, b).find("model"), std::string::npos);
  b = a;
  b.engine = "simbody";
  EXPECT_NE(sweepDifference(a, b).find("engine"), std::string::npos);
  b = a;
  b.sets = {"simulation.tau=10"};
  EXPECT_NE(sweepDifference(a, b).find("--set"), std::string::npos);
  b = a;
  b.grid = SweepGrid({parseVary("platform.friction.mu=0:1:12")});
  EXPECT_NE(sweepDifference(a, b).find("values"), std::string::npos);
  b = a;
  b.rig_text += "# changed\n";
  EXPECT_NE(sweepDifference(a, b).find("rig"), std::string::npos);
}

TEST(SweepRunner, EveryPointOnceWhateverTheThreads) {
  std::vector<long> todo;
  for (long g = 0; g < 200; ++g) todo.push_back(g);
  for (int jobs : {1, 2, 7}) {
    std::multiset<long> got;
    runSweepPoints(
        todo, jobs,
        [](long g) -> std::optional<SweepPoint> {
          if (g == 13) return std::nullopt;  // interrupted: not recorded
          SweepPoint p;
          p.index = g;
          return p;
        },
        [&](const SweepPoint& p) { got.insert(p.index); }, [] { return false; });
    EXPECT_EQ(got.size(), 199u) << jobs;
    EXPECT_EQ(got.count(13), 0u);
    EXPECT_EQ(got.count(199), 1u);
  }
  // an exception stops the sweep and comes back
  EXPECT_THROW(runSweepPoints(
                   todo, 3,
                   [](long g) -> std::optional<SweepPoint> {
                     if (g == 50) throw std::runtime_error("boom");
                     return SweepPoint{};
                   },
                   [](const SweepPoint&) {}, [] { return false; }),
               std::runtime_error);
}

TEST(SweepProgress, ShowsCountPercentAndEta) {
  const std::string s = progressText(250, 1000, 3, 50.0, 15.0, 80);
  EXPECT_NE(s.find("250/1000"), std::string::npos) << s;
  EXPECT_NE(s.find("25%"), std::string::npos) << s;
  EXPECT_NE(s.find("ETA 0:15"), std::string::npos) << s;
  EXPECT_NE(s.find("3 failed"), std::string::npos) << s;
  EXPECT_LE(s.size(), 80u);
  EXPECT_NE(progressText(1, 10, 0, 0.001, 9000, 80).find("ETA 2:30:00"), std::string::npos);
}

TEST(SweepMaps, EveryRegimeHasItsOwnColour) {
  std::map<long, SweepPoint> pts;
  const std::vector<std::string> names = {
      "in-phase", "antiphase",    "death",          "suppression",
      "failed",   "clusters:3+2", "clusters:2+1x3", "suppressed:1;in-phase"};
  for (size_t k = 0; k < names.size(); ++k) pts[k].regime = names[k];
  pts[20].regime = "clusters:3+2";
  const std::vector<std::string> legend = regimeLegendOrder(pts);
  ASSERT_EQ(legend.size(), names.size());
  EXPECT_EQ(legend.front(), "in-phase");  // SPEC names first
  EXPECT_EQ(legend[5], "clusters:3+2");   // then the most frequent
  std::set<std::string> colours;
  for (const auto& n : legend) colours.insert(regimeColour(n, legend));
  EXPECT_EQ(colours.size(), legend.size());
  const SweepGrid grid({parseVary("a=0:1:3"), parseVary("b=0:1:2")});
  const std::string script = regimeMapScript("d.dat", "m.png", grid, legend, "t");
  for (const auto& n : legend) EXPECT_NE(script.find("'" + n + "'"), std::string::npos) << n;
  EXPECT_NE(script.find("rgbimage"), std::string::npos);
}

// ---- the order parameter
// ---------------------------------------------------------------------------

TEST(OrderParameter, OneInPhaseZeroForASplayState) {
  EXPECT_DOUBLE_EQ(orderParameter({2.0, 2.0, 2.0}, {0.0, 2 * kPi}), 1.0);
  EXPECT_NEAR(orderParameter({2.0, 2.0, 2.0}, {2 * kPi / 3, 4 * kPi / 3}), 0.0, 1e-15);
  EXPECT_NEAR(orderParameter({1.0, 1.0}, {kPi}), 0.0, 1e-15);
  EXPECT_NEAR(orderParameter({3.0, 1.0}, {kPi}), 0.5, 1e-15);  // |3 - 1| / 4
  EXPECT_DOUBLE_EQ(orderParameter({1.7}, {}), 1.0);
  EXPECT_EQ(orderParameter({0.0, 0.0}, {1.0}), 0.0);  // nothing swings
}

// Identical metronomes on a platform held still keep their phases: the slow flow's r is 1 from
// an in-phase start and 0 from a splay start, on every row.
std::vector<EnvelopeRow> slowFlowRows(const std::vector<double>& phases) {
  ScaledRigInput in;
  in.epsilon = 0.05;
  in.friction = FrictionLaw::fixed();
  in.tau_end = 5.0;
  for (double phi : phases) {
    ScaledMetronomeInput m;
    m.nu = 0.7;
    m.J = 2.8;
    m.theta_c = 0.9;
    m.theta0 = 1.9 * std::sin(phi);
    m.thetadot0 = 1.9 * std::cos(phi);
    in.metronomes.push_back(m);
  }
  const ScaledParams p = computeScaled(rigFromScaled(in));
  MemorySink sink;
  SlowFlowOptions opt;
  opt.tau_end = p.tau_end;
  EXPECT_TRUE(runSlowFlow(p, opt, sink).complete);
  return sink.envelope;
}

TEST(OrderParameter, TheSlowFlowWritesItOnEveryRow) {
  const auto in_phase = slowFlowRows({0.4, 0.4, 0.4, 0.4});
  ASSERT_GT(in_phase.size(), 10u);
  for (const auto& r : in_phase) EXPECT_NEAR(r.r, 1.0, 1e-12) << r.tau;
  const auto splay = slowFlowRows({0.0, 2 * kPi / 5, 4 * kPi / 5, 6 * kPi / 5, 8 * kPi / 5});
  ASSERT_GT(splay.size(), 10u);
  for (const auto& r : splay) EXPECT_NEAR(r.r, 0.0, 1e-9) << r.tau;
  // and the file carries it at the end of each row
  const std::string path = scratchFile("env.csv");
  {
    std::ofstream out(path);
    out << envelopeHeader(5) << "\n" << formatEnvelopeRow(splay.back()) << "\n";
  }
  const auto back = readEnvelopeCsv(path);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_NEAR(back[0].r, 0.0, 1e-9);
  fs::remove(path);
}

TEST(OrderParameter, EnvelopeFilesWithoutItStillRead) {
  const std::string path = scratchFile("old_env.csv");
  std::ofstream(path) << "tau,A_1,A_2,psi_2\n0.1,2,2,3.141592653589793\n0.2,3,1,0\n";
  const auto rows = readEnvelopeCsv(path);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_NEAR(rows[0].r, 0.0, 1e-15);  // computed from A and psi
  EXPECT_NEAR(rows[1].r, 1.0, 1e-15);
  std::ofstream(path) << "tau,A_1,A_2,psi_2,r\n0.1,2,2,3.14,0.25\n";
  EXPECT_DOUBLE_EQ(readEnvelopeCsv(path)[0].r, 0.25);  // as written
  std::ofstream(path) << "tau,A_1,A_2,psi_2,q\n0.1,2,2,3.14,0.25\n";
  EXPECT_THROW(readEnvelopeCsv(path), std::runtime_error);
  fs::remove(path);
}

// ---- cluster names (N >= 3) on synthetic envelopes ---------------------------------------------

constexpr double kTauEnd = 100.0;

// Rows on the shared grid; phase(i, tau) of metronome i (psi_j = phi_1 - phi_j), A(i, tau).
RegimeVerdict judge(
    int n, std::function<double(int, double)> phase,
    std::function<double(int, double)> A = [](int, double) { return 1.9; }) {
  std::vector<EnvelopeRow> rows;
  for (long k = 0; envelopeTau(0.073, k) <= kTauEnd; ++k) {
    EnvelopeRow r;
    r.tau = envelopeTau(0.073, k);
    for (int i = 0; i < n; ++i) r.A.push_back(A(i, r.tau));
    for (int j = 1; j < n; ++j) r.psi.push_back(phase(0, r.tau) - phase(j, r.tau));
    rows.push_back(r);
  }
  return classifyRegime(rows, kTauEnd, 0.073, std::vector<double>(n, 0.9));
}

TEST(ClusterNames, GroupsWithinTwoTenthsOfARadianAreClusters) {
  // five metronomes: three near 0, two near pi (slightly spread, all locked)
  const double group[] = {0.0, 0.1, -0.1, kPi, kPi + 0.15};
  const RegimeVerdict v = judge(5, [&](int i, double) { return group[i]; });
  EXPECT_EQ(v.name, "clusters:3+2");
  EXPECT_EQ(v.cluster_sizes, (std::vector<int>{3, 2}));
  // the SPEC name where it applies: one cluster of all
  EXPECT_EQ(judge(4, [](int i, double) { return 0.05 * i; }).name, "in-phase");
  // a splay state: no two together, all locked
  const RegimeVerdict splay = judge(5, [](int i, double) { return 2 * kPi * i / 5; });
  EXPECT_EQ(splay.name, "splay");
  EXPECT_EQ(clusterText(splay.cluster_sizes), "1x5");
  // three together, the other two drifting away from them and from each other
  const RegimeVerdict d =
      judge(5, [](int i, double t) { return i < 3 ? 0.0 : (i == 3 ? 0.5 : -0.7) * t; });
  EXPECT_EQ(d.name, "drift");  // clusters must be locked to each other (docs/regimes.md)
  EXPECT_EQ(d.cluster_sizes, (std::vector<int>{3, 1, 1}));
  // all drifting apart: drift
  EXPECT_EQ(judge(3, [](int i, double t) { return 0.3 * i * t; }).name, "drift");
  // metronome 2 creeps away from 1 (by 0.3 over the window): no cluster, nothing settled
  EXPECT_EQ(judge(3, [](int i, double t) { return i == 2 ? 2.0 : (i ? 0.15 + 0.03 * t : 0); }).name,
            "unsettled");
}

TEST(ClusterNames, SuppressionAndDeathAreNamed) {
  // metronomes 2 and 5 below theta_c; the three others in phase
  auto A = [](int i, double) { return i == 1 || i == 4 ? 0.3 : 1.9; };
  const RegimeVerdict v = judge(
      5, [](int i, double) { return i == 1 ? kPi : 0.0; }, A);
  EXPECT_EQ(v.name, "suppressed:2;in-phase");
  EXPECT_EQ(v.regime, Regime::Suppression);  // the SPEC 4 class is kept
  EXPECT_EQ(v.dead, 2);
  // one alive
  EXPECT_EQ(judge(
                3, [](int, double) { return 0.0; }, [](int i, double) { return i ? 0.2 : 2.0; })
                .name,
            "suppressed:2");
  EXPECT_EQ(judge(
                4, [](int, double) { return 0.0; }, [](int, double) { return 0.1; })
                .name,
            "death");
  // the run-length form for many equal clusters
  EXPECT_EQ(clusterText({2, 1, 1, 1, 1}), "2+1x4");
  EXPECT_EQ(clusterText({3, 3, 3, 2, 1, 1}), "3x3+2+1+1");
}

TEST(ClusterNames, TwoMetronomesKeepTheSpecNames) {
  EXPECT_EQ(judge(2, [](int i, double) { return i ? kPi + 0.3 : 0.0; }).name, "antiphase");
  EXPECT_EQ(judge(2, [](int i, double) { return i ? 0.1 : 0.0; }).name, "in-phase");
  EXPECT_EQ(judge(2, [](int i, double) { return i ? 1.0 : 0.0; }).name, "phase-locked");
  EXPECT_EQ(judge(2, [](int i, double t) { return i ? 0.5 * t : 0.0; }).name, "drift");
  EXPECT_EQ(judge(
                2, [](int, double) { return 0.0; }, [](int i, double) { return i ? 0.5 : 2.0; })
                .name,
            "suppression");
  EXPECT_EQ(judge(
                2, [](int, double) { return 0.0; }, [](int, double) { return 0.5; })
                .name,
            "death");
}

}  // namespace
}  // namespace metrosync
