// The verdict against the peer (tools/bench/peer_verdict.h) on synthetic work-precision data
// whose answers are known in closed form: power laws time = a * error^-p on each side give the
// ratio at any error exactly (a line in log-log is what the interpolation assumes), cost per
// period c * N^k gives the slope k; and the never-extrapolate rule, the verdict, the guards and the
// CSV read-back. No simulation and no timing: seconds.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "base/csv.h"
#include "tools/bench/peer_verdict.h"
#include "tools/bench/peer_verdict_report.h"
#include "tools/bench/wp_csv.h"

namespace mb = metrosync::bench;

namespace {

constexpr double kRel = 1e-10;  // interpolation of exact power laws: rounding only

struct PowerLaw {
  double a, p;  // time = a * error^-p
  double at(double e) const { return a * std::pow(e, -p); }
};

// Points of one integrator at errors 10^lo_exp ... 10^hi_exp, `per_decade` per decade; the
// final-state error is the envelope error times `final_factor`, the CPU time the wall time
// times 0.8.
std::vector<mb::SidePoint> curve(const std::string& name, PowerLaw law, double lo_exp,
                                 double hi_exp, int per_decade, double final_factor = 10) {
  std::vector<mb::SidePoint> pts;
  const int k_max = static_cast<int>(std::lround((hi_exp - lo_exp) * per_decade));
  for (int k = 0; k <= k_max; ++k) {
    const double e = std::pow(10.0, lo_exp + static_cast<double>(k) / per_decade);
    mb::SidePoint s;
    s.method = name + ":" + std::to_string(k);
    s.err_final = e;
    s.err_envelope = e / final_factor;
    s.cpu_s = law.at(e);
    s.wall_s = law.at(e) / 0.8;
    s.runs = 5;
    pts.push_back(s);
  }
  return pts;
}

void append(std::vector<mb::SidePoint>& to, const std::vector<mb::SidePoint>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

mb::VerdictScene scene(const std::string& name, int n, double periods) {
  mb::VerdictScene s;
  s.name = name;
  s.n = n;
  s.periods = periods;
  s.reference_engine = "direct";
  s.reference = "direct:verner76:1e-13";
  s.cross_checks.push_back({"peer", "peer:rkf78:1e-13", 1e-11, 1e-12});
  return s;
}

const std::vector<double> kDecades = {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};

}  // namespace

TEST(PeerVerdict, RatioOfTwoPowerLawsIsExactAtEveryError) {
  // off-decade samples (3 per decade from 10^-2.9): every table error lies between two points
  const PowerLaw ours{2e-3, 0.25}, peer{1e-3, 0.40};
  mb::VerdictScene s = scene("s", 2, 30);
  s.ours = curve("direct:a", ours, -11.9, -2.9, 3);
  s.peer = curve("peer:b", peer, -11.9, -2.9, 3);
  for (auto clock : {mb::Clock::Cpu, mb::Clock::Wall}) {
    const mb::RatioTable t = mb::ratioTable({s}, mb::ErrorMeasure::FinalState, clock, kDecades);
    ASSERT_EQ(t.rows.size(), 1u);
    for (const mb::RatioCell& c : t.rows[0].cells) {
      // (1e-3 / 2e-3) * e^(0.25 - 0.40): the wall factor cancels
      const double want = 0.5 * std::pow(c.error, 0.25 - 0.40);
      ASSERT_TRUE(c.filled()) << c.error << " " << c.reason;
      EXPECT_NEAR(c.ratio, want, kRel * want) << c.error;
      EXPECT_NEAR(c.time_ours_s, (clock == mb::Clock::Cpu ? 1 : 1.25) * ours.at(c.error),
                  kRel * ours.at(c.error) * 1.25);
    }
  }
  // on the envelope measure the same points sit 10 times lower in error
  const mb::RatioTable te = mb::ratioTable({s}, mb::ErrorMeasure::Envelope, mb::Clock::Cpu, {1e-6});
  const double want = (1e-3 * std::pow(1e-5, -0.40)) / (2e-3 * std::pow(1e-5, -0.25));
  EXPECT_NEAR(te.rows[0].cells[0].ratio, want, kRel * want);
}

TEST(PeerVerdict, FrontTakesEachSidesCheapestIntegratorAtEachError) {
  // two integrators per side, crossing mid-range; sampled at the decades, where the front is
  // min(first, second) exactly
  const PowerLaw o1{1e-3, 0.35}, o2{1e-2, 0.20};  // cross at error 10^(-1/0.15) = 2.2e-7
  const PowerLaw p1{3e-3, 0.30}, p2{5e-4, 0.45};  // cross at 10^(-0.778/0.15) = 6.3e-6
  mb::VerdictScene s = scene("s", 8, 100);
  append(s.ours, curve("direct:o1", o1, -11, -3, 1));
  append(s.ours, curve("direct:o2", o2, -11, -3, 1));
  append(s.peer, curve("peer:p1", p1, -11, -3, 1));
  append(s.peer, curve("peer:p2", p2, -11, -3, 1));
  // a third, dominated integrator (slower at every error) changes nothing
  append(s.peer, curve("peer:slow", {9e-3, 0.45}, -11, -3, 4));
  const mb::RatioTable t =
      mb::ratioTable({s}, mb::ErrorMeasure::FinalState, mb::Clock::Cpu, kDecades);
  for (const mb::RatioCell& c : t.rows[0].cells) {
    const double want =
        std::min(p1.at(c.error), p2.at(c.error)) / std::min(o1.at(c.error), o2.at(c.error));
    EXPECT_NEAR(c.ratio, want, kRel * want) << c.error;
  }
}

TEST(PeerVerdict, NeverExtrapolatesAndSaysWhy) {
  mb::VerdictScene s = scene("s", 2, 30);
  s.ours = curve("direct:a", {1e-3, 0.3}, -8, -3, 2);  // 1e-8 ... 1e-3
  s.peer = curve("peer:b", {1e-3, 0.3}, -11, -5, 2);   // 1e-11 ... 1e-5
  const mb::RatioTable t =
      mb::ratioTable({s}, mb::ErrorMeasure::FinalState, mb::Clock::Cpu, kDecades);
  const auto& cells = t.rows[0].cells;
  EXPECT_FALSE(cells[0].filled());  // 1e-4: looser than the peer's cheapest run
  EXPECT_NE(cells[0].reason.find("the peer's cheapest run is already at 1.0e-05"),
            std::string::npos)
      << cells[0].reason;
  for (int k = 1; k <= 4; ++k) EXPECT_NEAR(cells[k].ratio, 1.0, kRel) << cells[k].error;
  for (int k = 5; k <= 6; ++k) {  // 1e-9, 1e-10: metrosync does not reach them
    EXPECT_FALSE(cells[k].filled());
    EXPECT_NE(cells[k].reason.find("metrosync does not reach it (its most accurate run: 1.0e-08)"),
              std::string::npos)
        << cells[k].reason;
  }
  // a looser run that costs more than a more accurate one is not on the front: no bracket for
  // 1e-4 even though a run at 1e-3 exists
  const auto front = mb::sideFront({{"a", 1e-3, 1e-3, 5.0, 5.0, 5}, {"b", 1e-5, 1e-5, 1.0, 1.0, 5}},
                                   mb::ErrorMeasure::FinalState, mb::Clock::Cpu);
  EXPECT_EQ(front.size(), 1u);
  EXPECT_NE(mb::coverageGap(front, 1e-4, "x"), "");
  EXPECT_EQ(mb::coverageGap(front, 1e-5, "x"), "");
  EXPECT_EQ(mb::coverageGap({}, 1e-5, "x"), "x has no timed run");
}

TEST(PeerVerdict, VerdictNamesWhereTheTargetIsMissed) {
  mb::VerdictScene fast = scene("fast", 2, 30), slow = scene("slow", 32, 30);
  fast.ours = curve("direct:a", {1e-3, 0.3}, -11, -3, 2);
  fast.peer = curve("peer:b", {2.5e-3, 0.3}, -11, -3, 2);  // ratio 2.5 everywhere
  mb::RatioTable t = mb::ratioTable({fast}, mb::ErrorMeasure::FinalState, mb::Clock::Cpu, kDecades);
  mb::Verdict v = mb::verdictOf(t);
  EXPECT_TRUE(v.met);
  EXPECT_EQ(v.cells, 7);
  EXPECT_NE(mb::verdictLine(t, v).find("MET in all 7 cells"), std::string::npos);
  EXPECT_NE(mb::ratioTableMarkdown(t).find("| 2.50 |"), std::string::npos);

  // ratio 2.5 * (e / 1e-7)^0.1: 2.5 at 1e-7, 1.986 at 1e-8, 1.577 at 1e-9
  slow.ours = curve("direct:a", {1e-3, 0.3}, -11, -3, 2);
  slow.peer = curve("peer:b", {2.5e-3 * std::pow(1e-7, -0.1), 0.2}, -9, -3, 2);
  t = mb::ratioTable({fast, slow}, mb::ErrorMeasure::FinalState, mb::Clock::Cpu, kDecades);
  v = mb::verdictOf(t);
  EXPECT_FALSE(v.met);
  EXPECT_EQ(v.cells, 14);
  EXPECT_EQ(v.below, 2);  // slow at 1e-8 and 1e-9
  EXPECT_EQ(v.empty, 1);  // slow at 1e-10: the peer stops at 1e-9
  EXPECT_NEAR(v.worst, 2.5 * std::pow(0.01, 0.1), 1e-9);
  EXPECT_EQ(v.worst_at, "slow at 1e-09");
  ASSERT_EQ(v.below_where.size(), 1u);
  EXPECT_EQ(v.below_where[0], "slow: 1e-08..1e-09");
  ASSERT_EQ(v.empty_where.size(), 1u);
  EXPECT_EQ(v.empty_where[0], "slow: 1e-10");
  const std::string md = mb::ratioTableMarkdown(t);
  EXPECT_NE(md.find("**1.99**"), std::string::npos) << md;
  EXPECT_NE(md.find("- slow, 1e-10: the peer does not reach it"), std::string::npos) << md;
  EXPECT_NE(mb::verdictLine(t, v).find("NOT MET"), std::string::npos);
}

TEST(PeerVerdict, SlopeOfCostPerPeriodAgainstN) {
  EXPECT_TRUE(std::isnan(mb::logLogSlope({2, 2}, {1, 3})));  // one distinct N
  EXPECT_NEAR(mb::logLogSlope({1, 10, 100}, {3, 30, 300}), 1.0, 1e-12);
  // time per period = c N^k e^-p; each scene its own number of periods
  const double k_ours = 1.3, k_peer = 1.0;
  std::vector<mb::VerdictScene> scenes;
  const std::vector<std::pair<std::string, int>> ns = {
      {"n128", 128}, {"experiment-short", 2}, {"n8", 8}, {"n32", 32}};
  for (const auto& [name, n] : ns) {
    const double periods = 10.0 + n;
    mb::VerdictScene s = scene(name, n, periods);
    s.ours = curve("direct:a", {periods * 1e-5 * std::pow(n, k_ours), 0.2}, -10, -3, 3);
    s.peer = curve("peer:b", {periods * 2e-5 * std::pow(n, k_peer), 0.2}, -10, -3, 3);
    scenes.push_back(s);
  }
  // a scene outside the N-scaling set, far off the law: left out
  mb::VerdictScene other = scene("experiment", 2, 600);
  other.ours = curve("direct:a", {1.0, 0.2}, -10, -3, 3);
  other.peer = other.ours;
  scenes.push_back(other);
  const auto rows = mb::nSlope(scenes, {"experiment-short", "n8", "n32", "n128"}, {1e-5, 1e-8},
                               mb::ErrorMeasure::FinalState, mb::Clock::Cpu);
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& r : rows) {
    ASSERT_EQ(r.ns, (std::vector<int>{2, 8, 32, 128}));
    EXPECT_NEAR(r.slope_ours, k_ours, 1e-9);
    EXPECT_NEAR(r.slope_peer, k_peer, 1e-9);
    const double want = 1e-5 * std::pow(2.0, k_ours) * std::pow(r.error, -0.2);
    EXPECT_NEAR(r.ours_per_period_s[0], want, kRel * want);
  }
}

TEST(PeerVerdict, GuardsOnRunsAndThePeersValidation) {
  mb::VerdictScene a = scene("a", 2, 30), b = scene("b", 8, 30), c = scene("c", 32, 30);
  for (auto* s : {&a, &b, &c}) {
    s->ours = curve("direct:x", {1e-3, 0.3}, -11, -3, 2);
    s->peer = curve("peer:y", {3e-3, 0.3}, -11, -3, 2);
  }
  b.cross_checks = {{"peer", "peer:rkf78:1e-13", 2e-8, 1e-10}};  // above 1e-8
  // c: a check of another engine (ignored) and one of the reference's own (its uncertainty, not
  // a validation of the peer)
  c.cross_checks = {{"simbody", "simbody:rk-merson:1e-12", 1e-9, 1e-10},
                    {"direct", "direct:dopri5:1e-13", 3e-8, 1e-9}};
  const auto ag = mb::peerAgreement({a, b, c}, mb::Sides{});
  ASSERT_EQ(ag.size(), 4u);
  EXPECT_TRUE(ag[0].validated);
  EXPECT_FALSE(ag[0].flagged());
  EXPECT_TRUE(ag[1].flagged());
  EXPECT_TRUE(ag[2].self);
  EXPECT_FALSE(ag[2].flagged());  // 3e-8, but the reference against itself
  EXPECT_FALSE(ag[3].validated);
  EXPECT_TRUE(ag[3].flagged());

  mb::VerdictPages p = mb::verdictPages({a, b, c}, mb::VerdictOptions{});
  ASSERT_EQ(p.warnings.size(), 2u);  // b's agreement, c's missing validation; runs are 5
  // the default table goes down to 1e-9: the bound is ten times below it
  EXPECT_NE(p.markdown.find("**FLAG: above 1e-10**"), std::string::npos);
  EXPECT_NE(p.verdict_line.find("MET in all 15 cells"), std::string::npos) << p.verdict_line;
  a.ours[3].runs = 3;
  p = mb::verdictPages({a, b, c}, mb::VerdictOptions{});
  ASSERT_EQ(p.warnings.size(), 3u);
  EXPECT_NE(p.warnings[0].find("as few as 3 runs"), std::string::npos) << p.warnings[0];
  // every cell of the four tables in ratios.csv: 3 scenes x 5 errors x 2 measures x 2 clocks
  int lines = 0;
  for (char ch : p.ratios_csv) lines += ch == '\n';
  EXPECT_EQ(lines, 1 + 3 * 5 * 4);
}

TEST(PeerVerdict, ReadsTheWorkPrecisionCsvBack) {
  const std::string header =
      "scene,n,periods,engine,integrator,setting,accuracy,steps_per_period,status,note,runs,"
      "wall_median_s,wall_min_s,wall_max_s,cpu_median_s,load1_min,load1_max,err_envelope,"
      "max_abs_dA,max_abs_dpsi,err_final_state,rows_compared,steps,rhs_evals,events,ticks,"
      "stick_slip,regime\n";
  const std::string text =
      header +
      "s,2,32.6,direct,verner76,1e-13,1e-13,,reference,,1,0.007,0.007,0.007,0.006,3.1,3.1,0,0,0,"
      "0,0,1,1,1,1,0,in-phase\n"
      "s,2,32.6,peer,rkf78,1e-13,1e-13,,cross-check,,1,0.005,0.005,0.005,0.005,3.1,3.1,1.5e-13,"
      "0,0,4e-13,33,1,1,1,1,0,in-phase\n"
      "s,2,32.6,direct,dopri5,1e-06,1e-06,,ok,,5,0.002,0.001,0.003,0.0015,2.5,3.7,1e-7,0,0,"
      "1e-6,33,1,1,1,1,0,\"a,b\"\n"
      "s,2,32.6,peer,dopri5,1e-06,1e-06,,ok,,4,0.004,0.001,0.005,0.003,2.9,3.2,2e-7,0,0,"
      "3e-6,33,1,1,1,1,0,x\n"
      "s,2,32.6,simbody,rk-merson,1e-06,1e-06,,ok,,5,0.4,0.4,0.4,0.4,2.9,3.2,2e-7,0,0,"
      "3e-6,33,1,1,1,1,0,x\n"
      "s,0,0,peer,dopri5,1e-12,1e-12,,skipped (predicted over budget),,0,,,,,,,,,,,,,,,,,\n";
  const auto scenes = mb::parseWorkPrecisionCsv(text, "wp-s.csv");
  ASSERT_EQ(scenes.size(), 1u);
  const mb::VerdictScene& s = scenes[0];
  EXPECT_EQ(s.n, 2);
  EXPECT_DOUBLE_EQ(s.periods, 32.6);
  EXPECT_EQ(s.reference, "direct:verner76:1e-13");
  ASSERT_EQ(s.cross_checks.size(), 1u);
  EXPECT_DOUBLE_EQ(s.cross_checks[0].err_final, 4e-13);
  ASSERT_EQ(s.ours.size(), 1u);  // simbody and the skipped point are not on either side
  ASSERT_EQ(s.peer.size(), 1u);
  EXPECT_DOUBLE_EQ(s.ours[0].err_final, 1e-6);
  EXPECT_DOUBLE_EQ(s.ours[0].err_envelope, 1e-7);
  EXPECT_DOUBLE_EQ(s.ours[0].cpu_s, 0.0015);
  EXPECT_DOUBLE_EQ(s.peer[0].wall_s, 0.004);
  EXPECT_EQ(s.peer[0].runs, 4);
  EXPECT_DOUBLE_EQ(s.load_min, 2.5);
  EXPECT_DOUBLE_EQ(s.load_max, 3.7);
  EXPECT_EQ(metrosync::csvCells("a,\"b,\"\"c\"\"\",d"),
            (std::vector<std::string>{"a", "b,\"c\"", "d"}));

  // a missing column and a malformed number name the file, the line and the column
  try {
    mb::parseWorkPrecisionCsv("scene,n\ns,2\n", "bad.csv");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv line 1: no column 'periods'"), std::string::npos)
        << e.what();
  }
  std::string broken = text;
  broken.replace(broken.find("0.0015"), 6, "0.00x5");
  try {
    mb::parseWorkPrecisionCsv(broken, "wp-s.csv");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("wp-s.csv line 4, column cpu_median_s"), std::string::npos)
        << e.what();
  }
}

// The headline of a target over rows counts the rows that miss it (it once printed "NOT met in 0
// of 6 rows" when all 6 missed: the count of rows that met it after the words "NOT met in").
TEST(PeerVerdict, RowsVerdictCountsTheRowsThatMiss) {
  EXPECT_EQ(mb::rowsVerdict(0, 6), "NOT met in 6 of 6 rows");
  EXPECT_EQ(mb::rowsVerdict(4, 6), "NOT met in 2 of 6 rows");
  EXPECT_EQ(mb::rowsVerdict(6, 6), "met in all 6 rows");
  EXPECT_EQ(mb::rowsVerdict(0, 0), "not measured");
}
