// The careful peer's answer read (tools/bench/peer_output.h), and the summary of one run of
// tools/bench/speed.sh (tools/bench/speed_summary.h): the numbers it quotes from the CSVs, what
// it says when a part is missing, and README.md's marked block rewritten in place. No
// simulation, no peer, no timing.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "tools/bench/peer_output.h"
#include "tools/bench/speed_summary.h"

namespace mb = metrosync::bench;

namespace {

// One line as the careful peer prints it (its README's scene, rkf78 at 1e-9, --repeat 5).
const std::string kPeerLine =
    "{\"N\": 2, \"method\": \"rkf78\", \"rtol\": 1e-09, \"atol\": 1e-09, \"t\": "
    "410.95890410958907, \"state\": [-1.1787326562459139, -1.2196531322737667, "
    "2.1771120265555899, 2.2352201166041326, 146.43648688778268, -4.2735569368846154], "
    "\"mode\": \"slip-\", \"wall_ms\": 14.6227, \"cpu_ms\": 1.3980, \"wall_ms_runs\": [15.4532, "
    "14.6227, 13.4044, 1.3593, 25.4239], \"steps\": 1573, \"rhs_calls\": 31192, \"events\": 402, "
    "\"restarts\": 402, \"kicks\": [134, 134], \"platform_events\": 134, \"stick_to_slip\": 0, "
    "\"slip_stops\": 134, \"stick_time\": 0}";

std::string errorOf(const std::string& text) {
  try {
    mb::parsePeerOutput(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

mb::SpeedInputs inputs() {
  mb::SpeedInputs in;
  in.ratios_csv =
      "measure,clock,scene,n,error,time_metrosync_s,time_peer_s,ratio,below_target,reason\n"
      "final-state,CPU,peer-n2,2,1e-05,1,2.5,2.5,0,\n"
      "final-state,CPU,peer-n2,2,1e-06,1,1.5,1.5,1,\n"
      "final-state,CPU,experiment-short,2,1e-06,1,3,3,0,\n"
      "final-state,CPU,experiment-short,2,1e-09,,2,,,metrosync does not reach it\n"
      "final-state,CPU,peer-n8,8,1e-05,1,2.25,2.25,0,\n"
      "final-state,CPU,peer-n8,8,1e-09,1,4,4,0,\n"
      "final-state,CPU,n32,32,1e-05,1,,,,\"the peer was not run: N = 32, the peer ...\"\n"
      "final-state,wall,peer-n2,2,1e-05,1,0.5,0.5,1,\n"
      "envelope,CPU,peer-n2,2,1e-05,1,0.1,0.1,1,\n";
  in.nslope_csv =
      "measure,clock,error,side,scene,n,time_per_period_s,slope\n"
      "final-state,CPU,1e-05,metrosync,experiment-short,2,1e-5,1.04\n"
      "final-state,CPU,1e-05,metrosync,n128,128,1e-3,1.04\n"
      "final-state,CPU,1e-08,metrosync,n8,8,1e-5,1.12\n"
      "final-state,CPU,1e-08,peer,n8,8,1e-5,3\n"
      "envelope,CPU,1e-05,metrosync,n8,8,1e-5,7\n";
  in.run_csv =
      "scene,variant,runs,wall_seconds,engine_seconds,ratio,process_wall_s,process_cpu_s,"
      "load1_min,load1_max,target,failure\n"
      "yaml/rigs/experiment.yaml,,11,0.05,0.045,1.11,0.06,0.055,0.5,0.9,1.15,\n"
      "yaml/rigs/bench/peer-n2.yaml,simulation.sample=100,11,0.004,0.003,1.33,0.01,0.009,0.4,"
      "1.2,1.15,\n"
      "yaml/rigs/bench/n8.yaml,,0,,,,,,,,1.15,\"exit 3: boom, badly\"\n";
  in.maps_csv =
      "map,points,runs,wall_s,cpu_s,target_s,load1_min,load1_max,failure\n"
      "full,4096,1,52.5,104,45,0.3,1.4,\n"
      "slow,10000,1,2.5,4.9,3,0.2,0.2,\n";
  // a work-precision file: its timed points' loads count, a point not run does not
  in.wp_csvs = {
      "scene,engine,runs,load1_min,load1_max\n"
      "peer-n2,direct,5,0.1,0.7\n"
      "peer-n2,peer,0,,\n"
      "peer-n2,direct,0,9,9\n"};
  in.date = "2026-11-26";
  in.commit = "abc1234";
  in.peer = "`../shared/peer` (peer.cpp sha256 0123456789ab...)";
  return in;
}

}  // namespace

TEST(PeerOutput, ReadsTheLineThePeerPrints) {
  const mb::PeerOutput p = mb::parsePeerOutput("peer: a warning first\n" + kPeerLine + "\n\n");
  EXPECT_EQ(p.n, 2);
  EXPECT_EQ(p.method, "rkf78");
  EXPECT_DOUBLE_EQ(p.t, 410.95890410958907);
  ASSERT_EQ(p.state.size(), 6u);
  EXPECT_DOUBLE_EQ(p.state[4], 146.43648688778268);   // x
  EXPECT_DOUBLE_EQ(p.state[5], -4.2735569368846154);  // x'
  EXPECT_DOUBLE_EQ(p.cpu_ms, 1.398);
  EXPECT_DOUBLE_EQ(p.wall_ms, 14.6227);
  EXPECT_EQ(p.wall_ms_runs.size(), 5u);
  EXPECT_EQ(p.rhs_calls, 31192);
  EXPECT_EQ(p.kicks, (std::vector<long>{134, 134}));
  EXPECT_EQ(p.slip_stops, 134);
  EXPECT_EQ(p.mode, "slip-");
}

TEST(PeerOutput, SaysWhatIsWrong) {
  EXPECT_NE(errorOf("").find("printed nothing"), std::string::npos);
  EXPECT_NE(errorOf("peer: N must be 1..8").find("not JSON"), std::string::npos);
  std::string no_cpu = kPeerLine;
  no_cpu.replace(no_cpu.find("\"cpu_ms\""), 8, "\"cpu_xx\"");
  EXPECT_NE(errorOf(no_cpu).find("no key 'cpu_ms'"), std::string::npos) << errorOf(no_cpu);
  std::string short_state = kPeerLine;
  short_state.replace(short_state.find("-1.1787326562459139, "), 21, "");
  EXPECT_NE(errorOf(short_state).find("'state' has 5 values, not 2N + 2 = 6"), std::string::npos)
      << errorOf(short_state);
  std::string text_steps = kPeerLine;
  text_steps.replace(text_steps.find("1573"), 4, "\"x\"");
  EXPECT_NE(errorOf(text_steps).find("'steps' is not an integer"), std::string::npos);
}

TEST(SpeedSummary, QuotesTheNumbersOfTheCsvs) {
  const mb::SpeedFacts f = mb::speedFacts(inputs());
  ASSERT_EQ(f.groups.size(), 2u);  // N = 2 and 8; n32 (peer not run) and other clocks left out
  EXPECT_EQ(f.groups[0].n, 2);
  EXPECT_EQ(f.groups[0].cells, 4);
  EXPECT_EQ(f.groups[0].met, 2);  // 2.5 and 3
  EXPECT_DOUBLE_EQ(f.groups[0].lo, 1.5);
  EXPECT_DOUBLE_EQ(f.groups[0].hi, 3.0);
  EXPECT_EQ(f.groups[1].met, 2);
  EXPECT_EQ(f.scenes, 3);
  EXPECT_DOUBLE_EQ(f.err_lo, 1e-9);
  EXPECT_DOUBLE_EQ(f.err_hi, 1e-5);
  EXPECT_DOUBLE_EQ(f.slope_lo, 1.04);  // metrosync's, final-state, CPU only
  EXPECT_DOUBLE_EQ(f.slope_hi, 1.12);
  EXPECT_EQ(f.slope_n_lo, 2);
  EXPECT_EQ(f.slope_n_hi, 128);
  EXPECT_EQ(f.run_rows, 2);  // the failed row is left out
  EXPECT_EQ(f.run_met, 1);
  EXPECT_DOUBLE_EQ(f.default_wall, 0.05);
  EXPECT_DOUBLE_EQ(f.full_map_s, 52.5);
  EXPECT_DOUBLE_EQ(f.slow_target_s, 3);
  EXPECT_DOUBLE_EQ(f.load_lo, 0.1);
  EXPECT_DOUBLE_EQ(f.load_hi, 1.4);

  const std::string p = mb::speedParagraph(f, inputs());
  for (const char* want :
       {"on 2026-11-26, commit abc1234", "load 0.1-1.4", "from 1e-05 to 1e-09",
        "1.50-3.00x the peer's speed with 2 metronomes and 2.25-4.00x the peer's speed with 8 "
        "metronomes over 3 scenes",
        "target of 2x is not met (4 of 6 cells)", "the careful peer `../shared/peer` (peer.cpp",
        "integrates in 50 ms", "Issue 36's targets: 1 of 3 met",
        "engine alone vs the peer, every scene the peer runs (CPU medians): 1.50-4.00x (5 of 6 "
        "cells, errors 1e-05 to 1e-09) (NOT met, target >= 2.0x",
        "takes 1.11-1.33x its engine's time", "met in 1 of 2",
        "64 x 64 full-model map takes 52.5 s (target 45 s)",
        "100 x 100 slow-flow map 2.5 s (target 3 s)"})
    EXPECT_NE(p.find(want), std::string::npos) << want << "\n" << p;
  EXPECT_EQ(p.find("N^"), std::string::npos) << "issue 36 drops the N-slope's target";
  EXPECT_EQ(p.find("The machine was busy"), std::string::npos) << "load 1.4 on 2 cores is not";
  mb::SpeedFacts busy = f;
  busy.load_hi = 9.5;
  EXPECT_NE(
      mb::speedParagraph(busy, inputs()).find("The machine was busy (1-minute load up to 9.5"),
      std::string::npos);
  for (const char* want : {"on 2026-11-26"})
    EXPECT_NE(p.find(want), std::string::npos) << want << "\n" << p;
}

TEST(SpeedSummary, SaysWhatWasNotMeasured) {
  mb::SpeedInputs in = inputs();
  in.ratios_csv.clear();  // no peer
  in.maps_csv.clear();    // --no-maps
  const mb::SpeedFacts f = mb::speedFacts(in);
  EXPECT_TRUE(f.groups.empty());
  EXPECT_TRUE(std::isnan(f.full_map_s));
  const std::string p = mb::speedParagraph(f, in);
  EXPECT_NE(p.find("The careful peer was not measured in this run"), std::string::npos) << p;
  EXPECT_NE(p.find("The maps were not timed in this run."), std::string::npos) << p;
  EXPECT_EQ(p.find("x the peer's speed"), std::string::npos) << p;
  const std::string page = mb::speedPage(f, in);
  EXPECT_NE(page.find("Not measured in this run (the peer was missing)"), std::string::npos);

  in.run_csv = "scene,variant\nx,y,z\n";  // a malformed CSV names itself and the line
  try {
    mb::speedFacts(in);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("run.csv line 2: 3 fields"), std::string::npos)
        << e.what();
  }
}

TEST(SpeedSummary, RewritesOnlyTheMarkedBlockOfTheReadme) {
  const std::string readme =
      "# metrosync\n\nintro\n\n<!-- speed:begin: generated by tools/bench/speed.sh -->\nold "
      "paragraph\nold line 2\n<!-- speed:end -->\n\n## Next\nkept\n";
  const std::string once =
      mb::replaceBetweenMarkers(readme, mb::kSpeedBegin, mb::kSpeedEnd, "new paragraph");
  EXPECT_EQ(once,
            "# metrosync\n\nintro\n\n<!-- speed:begin: generated by tools/bench/speed.sh -->\nnew "
            "paragraph\n<!-- speed:end -->\n\n## Next\nkept\n");
  // rewriting again with the same text changes nothing
  EXPECT_EQ(mb::replaceBetweenMarkers(once, mb::kSpeedBegin, mb::kSpeedEnd, "new paragraph\n"),
            once);
  // an empty block leaves the markers adjacent
  EXPECT_NE(mb::replaceBetweenMarkers(readme, mb::kSpeedBegin, mb::kSpeedEnd, "")
                .find("speed.sh -->\n<!-- speed:end -->"),
            std::string::npos);
  const auto fails = [](const std::string& text) {
    try {
      mb::replaceBetweenMarkers(text, mb::kSpeedBegin, mb::kSpeedEnd, "x");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(fails("no markers\n").find("no '<!-- speed:begin' marker"), std::string::npos);
  EXPECT_NE(fails("<!-- speed:end -->\n<!-- speed:begin -->\n").find("comes before"),
            std::string::npos);
  EXPECT_NE(fails(readme + readme).find("appears twice"), std::string::npos);
  EXPECT_NE(fails("<!-- speed:begin --> <!-- speed:end -->\n").find("lines of their own"),
            std::string::npos);
}
