// Issue 37: labels of the attractor, not of the window's timing. The slow flow's regime map of the
// experiment (docs/maps/psi0-mu-slow.png) had 92 isolated cells, 90 of them `uncoupled` inside the
// antiphase region: approaching antiphase, the board sticks once the drive falls below friction
// and psi freezes near pi, and whether that happened before the regime window decided the label.
// Here: the isolated-cell counter (sim/analysis/isolated_cells.h) on grids built for it, then the
// maps themselves -- the isolated cells of the flagship map, of a small fast map and of `figures`'
// exp1, and each cell's label at tau and at 2 tau wherever its state stood still in between.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "base/constants.h"
#include "sim/analysis/isolated_cells.h"
#include "tests/common/run_metrosync.h"
#include "tools/report/map_speckle.h"

namespace metrosync {
namespace {

using testing_support::runMetrosync;
using testing_support::scratchDir;
using testing_support::shellQuote;

const std::string kMapRig = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/experiment-map.yaml";

SweepGrid grid(const std::vector<std::string>& vary) {
  std::vector<SweepAxis> axes;
  for (const auto& v : vary) axes.push_back(parseVary(v));
  return SweepGrid(axes);
}

// ---- the counter --------------------------------------------------------------------------------

TEST(IsolatedCells, ACellWhoseFourNeighboursShareOneOtherLabel) {
  // 5 x 4 (first axis across the rows of this picture), index = row * 4 + column
  const SweepGrid g = grid({"a=0:4:5", "b=0:3:4"});
  std::vector<std::string> l = {
      "x", "x", "x", "x",  //
      "x", "y", "x", "x",  // (1,1): its four neighbours are x: isolated
      "x", "x", "x", "y",  // (2,3) is on the edge: three neighbours, not counted
      "x", "z", "x", "x",  // (3,1): neighbours x, x, x and (4,1) = w: not one label
      "x", "w", "x", "x",  // (4,1): on the edge
  };
  std::vector<IsolatedCell> cells = isolatedCells(g, {0, 1}, l);
  ASSERT_EQ(cells.size(), 1u);
  EXPECT_EQ(cells[0].index, 5);
  EXPECT_EQ(cells[0].label, "y");
  EXPECT_EQ(cells[0].neighbours, "x");
  // a neighbour with no point yet (an empty label) is not a neighbour of one label
  l[1] = "";
  EXPECT_TRUE(isolatedCells(g, {0, 1}, l).empty());
  // a checkerboard: every inner cell is isolated (3 x 2 inner cells)
  for (long k = 0; k < g.size(); ++k) l[k] = (k / 4 + k % 4) % 2 ? "p" : "q";
  EXPECT_EQ(isolatedCells(g, {0, 1}, l).size(), 6u);
  // the map's axes may be any two: across the second axis only, nothing has four neighbours
  EXPECT_TRUE(isolatedCells(g, {1}, l).empty());
}

TEST(IsolatedCells, AThirdAxisMakesSlicesThatAreNotNeighbours) {
  // a x b x c = 3 x 3 x 2: the cell (1,1) of the slice c = 0 is isolated in its slice only; the
  // slice c = 1 differs everywhere (never a neighbour on the map)
  const SweepGrid g = grid({"a=0:2:3", "b=0:2:3", "c=0,1"});
  std::vector<std::string> l(g.size());
  for (long k = 0; k < g.size(); ++k) {
    const std::vector<long> at = g.coordinates(k);
    l[k] = at[2] == 0 ? (at[0] == 1 && at[1] == 1 ? "y" : "x") : "z";
  }
  const std::vector<IsolatedCell> cells = isolatedCells(g, {0, 1}, l);
  ASSERT_EQ(cells.size(), 1u);
  EXPECT_EQ(g.coordinates(cells[0].index), (std::vector<long>{1, 1, 0}));
}

// ---- the maps -----------------------------------------------------------------------------------

// The sweep of experiment-map.yaml over psi0 (metronomes.0.start.phi) and mu, in `out`.
void sweepMap(const std::string& out, const std::string& phi, const std::string& mu,
              const std::string& more = "") {
  const auto r = runMetrosync(
      "sweep " + shellQuote(kMapRig) + " --vary metronomes.0.start.phi=" + phi +
      " --vary platform.friction.mu=" + mu + " " + more + " --jobs 2 -q --out " + shellQuote(out));
  ASSERT_EQ(r.code, 0) << r.err;
}

int uncoupledSpecks(const MapSpeckle& m) {
  int n = 0;
  for (const IsolatedCell& c : m.cells) n += c.label == "uncoupled";
  return n;
}

// The cells whose label differs at tau and 2 tau though their psi moved by less than 0.1 rad and
// every amplitude by less than 1% from tau to 2 tau (the "still" cells).
struct StillCells {
  long still = 0;       // cells whose state stood still from tau to 2 tau
  std::string changed;  // ... whose label changed all the same
};

StillCells stillCells(const std::string& dir_tau, const std::string& dir_twice) {
  const SweepManifest m = readSweepManifest(dir_tau);
  std::map<long, SweepPoint> a, b;
  forEachRegimesRow(dir_tau + "/regimes.csv", m.grid, m.metronomes,
                    [&](const SweepPoint& p) { a[p.index] = p; });
  forEachRegimesRow(dir_twice + "/regimes.csv", m.grid, m.metronomes,
                    [&](const SweepPoint& p) { b[p.index] = p; });
  StillCells s;
  for (const auto& [index, p] : a) {
    const auto q = b.find(index);
    if (q == b.end() || !p.complete || !q->second.complete) continue;
    const double dpsi = std::fabs(std::remainder(q->second.psi[0] - p.psi[0], kTwoPi));
    bool still = dpsi < 0.1;
    for (size_t i = 0; i < p.A.size(); ++i)
      still = still && std::fabs(q->second.A[i] - p.A[i]) < 0.01 * p.A[i];
    if (!still) continue;
    ++s.still;
    if (p.regime != q->second.regime)
      s.changed += "  index " + std::to_string(index) + ": " + p.regime + " at tau, " +
                   q->second.regime + " at 2 tau\n";
  }
  return s;
}

// The flagship map (README, docs/maps/psi0-mu-slow.png), 100 x 100 at the rig's tau = 305.6 and at
// 2 tau: at most 10 isolated cells (main had 92), and no still cell that changes its label (main:
// 2, a phase slip into antiphase inside the window at tau, `drift` there). About 12 s of CPU.
TEST(MapLabels, FlagshipSlowMapHoldsStill) {
  const std::string dir = scratchDir("maplabels", "flagship", true);
  sweepMap(dir + "/tau", "0:2pi:100:open", "0:3:100");
  sweepMap(dir + "/twice", "0:2pi:100:open", "0:3:100", "--set simulation.tau=611.2");
  const MapSpeckle m = mapSpeckle(dir + "/tau");
  EXPECT_LE(m.cells.size(), 10u) << speckleText(m, true);
  EXPECT_EQ(uncoupledSpecks(m), 0) << speckleText(m, true);
  const StillCells s = stillCells(dir + "/tau", dir + "/twice");
  EXPECT_GT(s.still, 9000);  // the test compares something: most cells have settled by tau
  EXPECT_TRUE(s.changed.empty()) << s.changed;
}

// A small map inside the antiphase region's speckle (16 x 16, psi0 from 1 to 2.5, mu to 0.5): no
// isolated cell (main: 9, every one `uncoupled` in antiphase); and at tau = 17 and 34, where some
// boards stick inside the window at 17 (main: 2 still cells that change, antiphase <-> uncoupled).
TEST(MapLabels, SmallMapHasNoSpeckleAndKeepsItsLabelsAtTwiceTau) {
  const std::string dir = scratchDir("maplabels", "small", true);
  sweepMap(dir + "/map", "1:2.5:16", "0:0.5:16");
  const MapSpeckle m = mapSpeckle(dir + "/map");
  EXPECT_EQ(m.cells.size(), 0u) << speckleText(m, true);
  sweepMap(dir + "/tau", "1:2.5:16", "0:0.5:16", "--set simulation.tau=17");
  sweepMap(dir + "/twice", "1:2.5:16", "0:0.5:16", "--set simulation.tau=34");
  const StillCells s = stillCells(dir + "/tau", dir + "/twice");
  EXPECT_GT(s.still, 50);
  EXPECT_TRUE(s.changed.empty()) << s.changed;
}

// `metrosync figures`' exp1 (40 x 40): no `uncoupled` speck (main: 8); the two cells left are the
// tip of the suppression tongue at mu = 0.69 and its mirror image (docs/regimes.md).
TEST(MapLabels, FiguresExp1HasNoUncoupledSpeckle) {
  const std::string dir = scratchDir("maplabels", "exp1", true);
  const auto r = runMetrosync("figures --only exp1 --jobs 2 -q --out " + shellQuote(dir));
  ASSERT_EQ(r.code, 0) << r.err;
  const MapSpeckle m = mapSpeckle(dir + "/exp1-sweep");
  EXPECT_EQ(m.labels.size(), 1600u);
  EXPECT_LE(m.cells.size(), 2u) << speckleText(m, true);
  EXPECT_EQ(uncoupledSpecks(m), 0) << speckleText(m, true);
}

}  // namespace
}  // namespace metrosync
