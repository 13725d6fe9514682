// Issue 37, item 9: the plots a first try drew wrong, through their gnuplot scripts (the text
// gnuplot is given: what each axis and key says, which ranges are set).
#include <gtest/gtest.h>

#include <optional>

#include "sim/analysis/sweep.h"
#include "tools/report/figures.h"
#include "tools/report/full_continuation_report.h"
#include "tools/report/network_plot.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

const std::string kSource = METROSYNC_SOURCE_DIR;

// A network's order and raster plots: seconds on the x axis (a network is physical), tau on the
// top axis, and the axis ends where the data end (no axis past the last sample).
TEST(FirstTriesPlots, NetworkPlotsRunInSecondsToTheLastSample) {
  const std::string path = kSource + "/yaml/rigs/two-swings.yaml";
  const std::optional<Network> net = loadPlatformsNetwork(readRigFile(path), path, {}, {});
  ASSERT_TRUE(net);
  NetworkPlotAxes axes;
  axes.style.seconds_per_tau = 7.5;
  axes.tau_end = 2.0;  // the last sample: 15 s
  for (const std::string& s : {networkOrderScript(*net, axes, "t", "d", "o.png"),
                               networkRasterScript(*net, axes, "t", "d", "r.png")}) {
    EXPECT_NE(s.find("set xlabel 'time (s); top axis: slow time τ'"), std::string::npos) << s;
    EXPECT_NE(s.find("set xrange [0:15]"), std::string::npos) << s;
    EXPECT_NE(s.find("set x2range [0:2]"), std::string::npos) << s;
    EXPECT_NE(s.find("using (($1)*7.5):"), std::string::npos) << s;
    EXPECT_EQ(s.find("set xlabel 'tau'"), std::string::npos) << s;
  }
}

// exp1's key is printed as written (noenhanced): psi0's subscript is a character, not "_0".
TEST(FirstTriesPlots, Exp1KeySaysPsiZeroWithItsSubscript) {
  RegimeMapResult m;
  m.spec = regimeMapSpec(true);
  m.model = "slow";
  m.grid = SweepGrid(
      {parseVary("platform.friction.mu=0:3:4"), parseVary("metronomes.0.start.phi=0:2pi:4:open")});
  const std::string s =
      mapScript(m, FiguresContext{"slow", "", {0.23}}, {"in-phase"}, "d", "o", false);
  EXPECT_EQ(s.find("ψ_0"), std::string::npos) << s;
  EXPECT_NE(s.find("title 'exp1 panels: ψ₀ = 0, π'"), std::string::npos) << s;
}

// continue --model full's branches.png: one set of margins for every panel (their axes line up
// whatever each key's width), and the |mu| = 1 border a curve of its panel, not an arrow drawn
// across the others.
TEST(FirstTriesPlots, FullContinuationPanelsShareTheirMargins) {
  orbit::FullContinuation r;
  r.param = "platform.friction.mu";
  r.metronomes = 2;
  r.section_name = "theta_1 = 0, rising";
  const std::string s = fullDiagramScript(r, "d", "b.png");
  EXPECT_EQ(s.find("set arrow"), std::string::npos) << s;
  const std::size_t multiplot = s.find("set multiplot");
  ASSERT_NE(multiplot, std::string::npos);
  const std::size_t lmargin = s.find("set lmargin at screen"),
                    rmargin = s.find("set rmargin at screen");
  EXPECT_LT(lmargin, multiplot) << s;
  EXPECT_LT(rmargin, multiplot) << s;
  EXPECT_EQ(s.find("margin", multiplot), std::string::npos) << "no panel sets its own: " << s;
  EXPECT_EQ(s.find("key outside"), std::string::npos) << s;
  EXPECT_NE(s.find("1 with lines dt 3 lc rgb 'gray30' title '|mu| = 1'"), std::string::npos) << s;
}

}  // namespace
}  // namespace metrosync
