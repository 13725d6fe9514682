// The verdict against the careful peer (issue 23; tools/bench/peer_verdict.h) on synthetic
// work-precision data: the final-state comparison times each side's runs without samples, the
// envelope comparison its recording runs; a scene the peer cannot run is a row with its reason
// that no verdict counts; each scene gets its own verdict line; the envelope tables are left out
// when the peer reports no envelope; the peer's validation must sit far below the compared
// errors. No simulation, no timing.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "tools/bench/peer_verdict.h"
#include "tools/bench/peer_verdict_report.h"
#include "tools/bench/wp_csv.h"

namespace mb = metrosync::bench;

namespace {

constexpr double kRel = 1e-10;  // interpolation of exact power laws: rounding only
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const std::vector<double> kErrors = {1e-5, 1e-6, 1e-7, 1e-8, 1e-9};

// time = a * error^-p at errors 10^lo .. 10^hi, two per decade; the runs without samples take
// `final_factor` of the recording runs' time (NaN: not measured); envelope error = error / 10
std::vector<mb::SidePoint> curve(const std::string& name, double a, double p, double lo, double hi,
                                 double final_factor, bool envelope = true) {
  std::vector<mb::SidePoint> pts;
  for (int k = 0; k <= static_cast<int>(std::lround((hi - lo) * 2)); ++k) {
    const double e = std::pow(10.0, lo + 0.5 * k);
    mb::SidePoint s;
    s.method = name + ":" + std::to_string(k);
    s.err_final = e;
    s.err_envelope = envelope ? e / 10 : kNaN;
    s.cpu_s = a * std::pow(e, -p);
    s.wall_s = 2 * s.cpu_s;
    s.cpu_final_s = final_factor * s.cpu_s;
    s.wall_final_s = final_factor * s.wall_s;
    s.runs = 5;
    pts.push_back(s);
  }
  return pts;
}

mb::VerdictScene scene(const std::string& name, int n) {
  mb::VerdictScene s;
  s.name = name;
  s.n = n;
  s.periods = 10;
  s.reference_engine = "direct";
  s.reference = "direct:verner76:1e-13";
  return s;
}

}  // namespace

TEST(CarefulPeerVerdict, FinalStateRatiosUseTheRunsWithoutSamples) {
  // metrosync's runs without samples take 0.6 of its recording runs' time; the peer has one
  // timing (final factor 1): the final-state ratio is 3 / 0.6 = 5, the envelope ratio 3
  mb::VerdictScene s = scene("s", 2);
  s.ours = curve("direct:a", 1e-3, 0.3, -11, -3, 0.6);
  s.peer = curve("peer:b", 3e-3, 0.3, -11, -3, 1.0);
  const auto fin = mb::ratioTable({s}, mb::ErrorMeasure::FinalState, mb::Clock::Cpu, kErrors);
  const auto env = mb::ratioTable({s}, mb::ErrorMeasure::Envelope, mb::Clock::Cpu, {1e-6});
  for (const mb::RatioCell& c : fin.rows[0].cells) EXPECT_NEAR(c.ratio, 5.0, 5 * kRel) << c.error;
  EXPECT_NEAR(env.rows[0].cells[0].ratio, 3.0, 3 * kRel);
  // a point whose runs without samples were not measured falls back on its recording runs
  for (auto& p : s.ours) p.cpu_final_s = kNaN;
  const auto old = mb::ratioTable({s}, mb::ErrorMeasure::FinalState, mb::Clock::Cpu, {1e-6});
  EXPECT_NEAR(old.rows[0].cells[0].ratio, 3.0, 3 * kRel);
}

TEST(CarefulPeerVerdict, ASceneThePeerCannotRunIsARowWithItsReasonAndNoCells) {
  mb::VerdictScene a = scene("peer-n2", 2), big = scene("n32", 32);
  a.ours = curve("direct:a", 1e-3, 0.3, -11, -3, 1);
  a.peer = curve("peer:b", 2.5e-3, 0.3, -11, -3, 1);  // 2.5x everywhere
  big.ours = curve("direct:a", 1e-2, 0.3, -11, -3, 1);
  big.peer_skipped = "N = 32: the peer is compiled for 1..8 metronomes";
  const auto t = mb::ratioTable({a, big}, mb::ErrorMeasure::FinalState, mb::Clock::Cpu, kErrors);
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[1].skipped, big.peer_skipped);
  for (const auto& c : t.rows[1].cells) {
    EXPECT_FALSE(c.filled());
    EXPECT_EQ(c.reason.rfind(mb::kPeerNotRun, 0), 0u) << c.reason;
  }
  const mb::Verdict v = mb::verdictOf(t);
  EXPECT_TRUE(v.met) << "the skipped row is not an empty cell of the verdict";
  EXPECT_EQ(v.cells, 5);
  EXPECT_NE(mb::verdictLine(t, v).find("on 1 scenes): MET in all 5 cells"), std::string::npos)
      << mb::verdictLine(t, v);
  EXPECT_NE(mb::ratioTableMarkdown(t).find("| n32 | 32 | peer not run: N = 32"), std::string::npos);
  EXPECT_EQ(mb::sceneVerdictLine(t.rows[0]), "peer-n2 (N = 2): MET, 2.50x in all 5 cells.");
  EXPECT_NE(mb::sceneVerdictLine(t.rows[1]).find("n32 (N = 32): the peer was not run"),
            std::string::npos);
  // the validation table says why there is no cross-check there, and flags nothing
  const auto ag = mb::peerAgreement({a, big}, mb::Sides{});
  ASSERT_EQ(ag.size(), 2u);
  EXPECT_TRUE(ag[0].flagged()) << "peer-n2 has no cross-check of the peer";
  EXPECT_FALSE(ag[1].flagged());
  EXPECT_EQ(ag[1].skipped, big.peer_skipped);
  // a scene where the peer was not asked for at all (no points, no reason) is not validated nor
  // flagged: it is not in the table
  mb::VerdictScene alone = scene("alone", 2);
  alone.ours = a.ours;
  EXPECT_TRUE(mb::peerAgreement({alone}, mb::Sides{}).empty());
}

TEST(CarefulPeerVerdict, EachSceneHasItsOwnVerdictLine) {
  // ratio 2.5 (e / 1e-7)^0.1: 2.5 at 1e-7, below 2 at 1e-8 and 1e-9; the peer stops at 1e-9
  mb::VerdictScene s = scene("peer-n8", 8);
  s.ours = curve("direct:a", 1e-3, 0.3, -11, -3, 1);
  s.peer = curve("peer:b", 2.5e-3 * std::pow(1e-7, -0.1), 0.2, -9, -3, 1);
  mb::VerdictScene good = scene("peer-n2", 2);
  good.ours = s.ours;
  good.peer = curve("peer:b", 4e-3, 0.3, -11, -3, 1);
  const auto t = mb::ratioTable({s, good}, mb::ErrorMeasure::FinalState, mb::Clock::Cpu,
                                {1e-7, 1e-8, 1e-9, 1e-10});
  ASSERT_EQ(t.rows.size(), 2u);  // by N: peer-n2 first
  EXPECT_EQ(mb::sceneVerdictLine(t.rows[0]), "peer-n2 (N = 2): MET, 4.00x in all 4 cells.");
  EXPECT_EQ(mb::sceneVerdictLine(t.rows[1]),
            "peer-n8 (N = 8): NOT MET, 1.58-2.50x; below 2.0 at 1e-08..1e-09; not measured on "
            "both sides at 1e-10.");
}

TEST(CarefulPeerVerdict, EnvelopeTablesAreLeftOutWhenThePeerReportsNoEnvelope) {
  mb::VerdictScene s = scene("peer-n2", 2);
  s.ours = curve("direct:a", 1e-3, 0.3, -11, -3, 0.5);
  s.peer = curve("peer:b", 3e-3, 0.3, -11, -3, 1, false);
  s.cross_checks = {{"peer", "peer:rkf78:1e-13", 5e-12, kNaN}};
  EXPECT_TRUE(mb::peerMeasured({s}, mb::ErrorMeasure::FinalState));
  EXPECT_FALSE(mb::peerMeasured({s}, mb::ErrorMeasure::Envelope));
  const mb::VerdictPages p = mb::verdictPages({s}, mb::VerdictOptions{});
  EXPECT_NE(p.markdown.find("Not compared: the peer (peer) reports no envelope error."),
            std::string::npos)
      << p.markdown;
  EXPECT_EQ(p.markdown.find("## Equal envelope error, CPU"), std::string::npos);
  // ratios.csv: the final-state tables only (CPU and wall, 5 errors each)
  int lines = 0;
  for (char ch : p.ratios_csv) lines += ch == '\n';
  EXPECT_EQ(lines, 1 + 2 * 5);
  EXPECT_TRUE(p.warnings.empty()) << p.warnings.front();
  EXPECT_NE(p.verdict_line.find("MET in all 5 cells"), std::string::npos) << p.verdict_line;
  ASSERT_EQ(p.scene_lines.size(), 1u);
  EXPECT_EQ(p.scene_lines[0], "peer-n2 (N = 2): MET, 6.00x in all 5 cells.");
  EXPECT_NE(p.verdicts_markdown.find(p.verdict_line), std::string::npos);
  EXPECT_NE(p.verdicts_markdown.find("| peer-n2 | 2 | 6.00 |"), std::string::npos)
      << p.verdicts_markdown;
}

TEST(CarefulPeerVerdict, ThePeersValidationMustSitFarBelowTheComparedErrors) {
  EXPECT_DOUBLE_EQ(mb::agreementBound({1e-5, 1e-9}), 1e-10);
  EXPECT_DOUBLE_EQ(mb::agreementBound({1e-3, 1e-4}), mb::kPeerAgreement);  // 1e-8 is tighter
  mb::VerdictScene s = scene("s", 2);
  s.ours = curve("direct:a", 1e-3, 0.3, -11, -3, 1);
  s.peer = curve("peer:b", 3e-3, 0.3, -11, -3, 1, false);
  s.cross_checks = {{"peer", "peer:rkf78:1e-13", 5e-10, kNaN}};  // within 1e-8, not 1e-10
  const auto ag = mb::peerAgreement({s}, mb::Sides{}, mb::agreementBound(kErrors));
  ASSERT_EQ(ag.size(), 1u);
  EXPECT_TRUE(ag[0].flagged());
  const mb::VerdictPages p = mb::verdictPages({s}, mb::VerdictOptions{});
  ASSERT_EQ(p.warnings.size(), 1u);
  EXPECT_NE(p.warnings[0].find("by 5.0e-10 in final state (> 1e-10)"), std::string::npos)
      << p.warnings[0];
}

TEST(CarefulPeerVerdict, SlopeLinesAgainstTheTarget) {
  // cost per period c N^k: 1.05 is within 1.0-1.1, 1.3 is not
  for (const double k : {1.05, 1.3}) {
    std::vector<mb::VerdictScene> scenes;
    for (const auto& [name, n] : std::vector<std::pair<std::string, int>>{
             {"experiment-short", 2}, {"n8", 8}, {"n32", 32}}) {
      mb::VerdictScene s = scene(name, n);
      s.ours = curve("direct:a", 10 * 1e-5 * std::pow(n, k), 0.2, -10, -3, 1);
      if (n <= 8)
        s.peer = curve("peer:b", 1e-4 * n, 0.2, -10, -3, 1, false);
      else
        s.peer_skipped = "N = 32: the peer is compiled for 1..8 metronomes";
      scenes.push_back(s);
    }
    const mb::VerdictPages p = mb::verdictPages(scenes, mb::VerdictOptions{});
    ASSERT_EQ(p.slope_lines.size(), 3u);
    const std::string want = k < 1.1 ? "target 1.0-1.1: met." : "target 1.0-1.1: NOT met.";
    for (const std::string& l : p.slope_lines) {
      EXPECT_NE(l.find(want), std::string::npos) << l;
      EXPECT_NE(l.find(k < 1.1 ? "N^1.05 over 3 scenes" : "N^1.30 over 3 scenes"),
                std::string::npos)
          << l;
    }
    EXPECT_NE(p.markdown.find("(peer: not run)"), std::string::npos);
  }
}

TEST(CarefulPeerVerdict, ReadsTheFinalStateTimingsAndThePeersSkippedScenes) {
  const std::string text =
      "scene,n,periods,engine,integrator,setting,accuracy,steps_per_period,status,note,runs,"
      "wall_median_s,wall_min_s,wall_max_s,cpu_median_s,load1_min,load1_max,err_envelope,"
      "max_abs_dA,max_abs_dpsi,err_final_state,rows_compared,steps,rhs_evals,events,ticks,"
      "stick_slip,regime,wall_final_median_s,cpu_final_median_s,final_sampled_diff\n"
      "n32,32,100,direct,dopri5,1e-06,1e-06,,ok,,5,0.02,0.02,0.03,0.019,1,1,1e-5,0,0,1e-4,100,1,"
      "1,1,1,0,x,0.011,0.0105,0\n"
      "n32,32,100,peer,rkf78,1e-06,1e-06,,not run,\"N = 32: the peer is compiled for 1..8 "
      "metronomes\",0,,,,,,,,,,,,,,,,,,,,\n";
  const auto scenes = mb::parseWorkPrecisionCsv(text, "wp-n32.csv");
  ASSERT_EQ(scenes.size(), 1u);
  ASSERT_EQ(scenes[0].ours.size(), 1u);
  EXPECT_DOUBLE_EQ(scenes[0].ours[0].cpu_final_s, 0.0105);
  EXPECT_DOUBLE_EQ(scenes[0].ours[0].wall_final_s, 0.011);
  EXPECT_DOUBLE_EQ(scenes[0].ours[0].cpu_s, 0.019);
  EXPECT_TRUE(scenes[0].peer.empty());
  EXPECT_EQ(scenes[0].peer_skipped, "N = 32: the peer is compiled for 1..8 metronomes");
}
