// Issue 16's smaller items: the section-3A rig's decay slope and the mu-bar it implies (against
// the paper's closed form), plot formats, the heatmap above 8 metronomes, seconds on the plot
// axes, and the progress lines of long work.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/constants.h"
#include "tests/common/run_metrosync.h"
#include "tools/report/plot.h"
#include "tools/report/progress_log.h"
#include "yaml/rig_loader.h"

namespace {

namespace fs = std::filesystem;
using metrosync::kPi;
using metrosync::testing_support::CommandResult;
using metrosync::testing_support::runMetrosync;
using metrosync::testing_support::slurp;
using nlohmann::json;

std::string scratch(const std::string& name) {
  return metrosync::testing_support::scratchDir("small", name, true);
}

CommandResult metrosync(const std::string& args, const std::string& cwd) {
  return runMetrosync(args, {cwd, ""});
}

json readJson(const std::string& path) {
  std::ifstream in(path);
  return json::parse(in);
}

const std::string kSprings = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/board-on-springs.yaml";

// The paper's section 3A: slope = 4 mu-bar M g / (T kappa) with T = 2 pi sqrt(M / kappa), and the
// same slope written mu-bar T g / pi^2; the run's fitted slope must give back the rig's mu-bar.
TEST(Section3A, SlopeAndMuBarMatchTheClosedForm) {
  const std::string dir = scratch("springs");
  for (const std::string mu : {"6.5e-4", "4.6e-3"}) {
    const std::string set = "--set platforms.0.friction.mu=" + mu;
    const CommandResult r = metrosync("run " + metrosync::testing_support::shellQuote(kSprings) +
                                          " " + set + " --no-plot -q --out o" + mu,
                                      dir);
    ASSERT_EQ(r.code, 0) << r.err;
    const json s = readJson(dir + "/o" + mu + "/summary.json");
    ASSERT_TRUE(s.contains("section3a")) << mu;
    const metrosync::Rig rig = metrosync::loadRigFile(kSprings, {set.substr(6)});
    const double M = rig.totalMass(), g = rig.gravity_m_s2, kappa = rig.platform.spring_N_m;
    const double T = 2 * kPi * std::sqrt(M / kappa);
    const double slope = 4 * rig.platform.friction.valueOr("mu", 0.0) * M * g / (T * kappa);
    EXPECT_NEAR(slope, rig.platform.friction.valueOr("mu", 0.0) * T * g / (kPi * kPi), 1e-15);
    EXPECT_NEAR(s["section3a"]["slope"].get<double>(), slope, 1e-4 * slope) << mu;
    EXPECT_NEAR(s["section3a"]["mu_bar"].get<double>(), std::stod(mu), 1e-4 * std::stod(mu));
    EXPECT_NEAR(s["section3a"]["period"].get<double>(), T, 1e-12 * T);
    EXPECT_GE(s["section3a"]["extremes"].get<int>(), 5);
  }
  // a rig whose metronomes swing is not section 3A: no key
  ASSERT_EQ(metrosync("run --set simulation.duration=0.5 --no-plot -q --out plain", dir).code, 0);
  EXPECT_FALSE(readJson(dir + "/plain/summary.json").contains("section3a"));
}

bool startsWith(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

TEST(PlotFormat, SvgAndPdfOnRequestPngByDefault) {
  ASSERT_FALSE(metrosync::findExecutable("gnuplot").empty()) << "gnuplot is required (CI has it)";
  const std::string dir = scratch("formats");
  const std::string base = "--set simulation.duration=2 -q --engine direct";
  ASSERT_EQ(metrosync("run " + base + " --out png", dir).code, 0);
  ASSERT_EQ(metrosync("run " + base + " --plot-format svg --out svg", dir).code, 0);
  ASSERT_EQ(
      metrosync("compare --set simulation.duration=2 -q --plot-format pdf --out pdf", dir).code, 0);
  EXPECT_TRUE(startsWith(slurp(dir + "/png/envelope.png"), "\x89PNG"));
  const std::string svg = slurp(dir + "/svg/envelope.svg");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir + "/svg/envelope.png"));
  EXPECT_TRUE(startsWith(slurp(dir + "/pdf/comparison.pdf"), "%PDF"));
  const json files = readJson(dir + "/svg/summary.json")["files"];
  EXPECT_EQ(files.back(), "summary.json");
  bool listed = false;
  for (const auto& f : files) listed |= f == "envelope.svg";
  EXPECT_TRUE(listed);
  // physical rig: seconds on the axis, tau on the second axis
  EXPECT_NE(svg.find("time (s)"), std::string::npos);
  EXPECT_NE(svg.find("slow time"), std::string::npos);
  const CommandResult bad = metrosync("run " + base + " --plot-format gif --out gif", dir);
  EXPECT_EQ(bad.code, 2);
  EXPECT_FALSE(fs::exists(dir + "/gif"));
}

TEST(PlotFormat, SweepMapsInPdf) {
  const std::string dir = scratch("sweep");
  std::ofstream(dir + "/pair.yaml")
      << "units: scaled\nepsilon: 0.073\nplatform:\n  friction: {law: coulomb, mu: 0.4}\n"
         "metronomes:\n  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: 1.9, phi: 0.03}}\n"
         "  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: 1.9, phi: 3.0}}\nsimulation:\n  tau: 20\n";
  const CommandResult r = metrosync(
      "sweep pair.yaml --vary platform.friction.mu=0.1:0.5:3 --plot-format pdf -q --out s", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(startsWith(slurp(dir + "/s/regimes.pdf"), "%PDF"));
  EXPECT_TRUE(startsWith(slurp(dir + "/s/amplitudes.pdf"), "%PDF"));
  EXPECT_FALSE(fs::exists(dir + "/s/regimes.png"));
  // a png sweep into the same folder replaces the pdf maps (stale files of any format go)
  ASSERT_EQ(metrosync("sweep pair.yaml --vary platform.friction.mu=0.1:0.5:3 -q --out s", dir).code,
            0);
  EXPECT_TRUE(fs::exists(dir + "/s/regimes.png"));
  EXPECT_FALSE(fs::exists(dir + "/s/regimes.pdf"));
}

TEST(PlotFormat, HeatmapAboveEightMetronomes) {
  const std::vector<double> tc(9, 0.9), tc8(8, 0.9);
  const std::string many = metrosync::gnuplotScript("d", "p", 9, 1, tc, 10, 0, 2 * kPi, "t");
  const std::string eight = metrosync::gnuplotScript("d", "p", 8, 1, tc8, 10, 0, 2 * kPi, "t");
  EXPECT_NE(many.find("boxxyerror"), std::string::npos);
  EXPECT_EQ(many.find("title 'A_"), std::string::npos) << "no legend entry per metronome";
  EXPECT_EQ(many.find("title 'ψ_3"), std::string::npos);
  EXPECT_EQ(eight.find("boxxyerror"), std::string::npos);
  EXPECT_NE(eight.find("title 'A_8'"), std::string::npos);
  // and gnuplot draws it: a 9-metronome run
  const std::string dir = scratch("heatmap");
  const CommandResult r =
      metrosync("run " +
                    metrosync::testing_support::shellQuote(std::string(METROSYNC_SOURCE_DIR) +
                                                           "/yaml/rigs/n32.yaml") +
                    " --model slow --set simulation.duration=20 --plot-format svg -q --out o",
                dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string svg = slurp(dir + "/o/envelope.svg");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_EQ(svg.find("A_17"), std::string::npos);
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
}

TEST(ProgressLog, ALineEveryTenPercentAfterTheQuietTime) {
  std::vector<std::string> lines;
  metrosync::ProgressLog log(
      "run", "tau", 300, [&](const std::string& l) { lines.push_back(l); }, 1.0);
  log.update(45, 0.5);  // 15%: the 10% mark passed within the quiet second, not written
  EXPECT_TRUE(lines.empty());
  log.update(31, 2.0);  // past 10%, written quietly already: nothing
  EXPECT_TRUE(lines.empty());
  log.update(95, 2.0);  // 31.7%: the 30% line; remaining = 2 (1 - f) / f = 4.3 s
  log.update(96, 2.1);  // still 30%: nothing new
  log.update(300, 20.0);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "metrosync: run 30% (tau 95 of 300), elapsed 0:02, remaining 0:04");
  EXPECT_NE(lines[1].find("run 100%"), std::string::npos);
  EXPECT_NE(lines[1].find("remaining 0:00"), std::string::npos);
  EXPECT_EQ(metrosync::clockText(3725), "1:02:05");
}

}  // namespace
