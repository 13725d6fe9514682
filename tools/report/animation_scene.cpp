#include "tools/report/animation_scene.h"

#include <algorithm>
#include <cmath>

namespace metrosync::animation {

namespace {

// The proportions of the drawing, in units of the longest pendulum u (its pivot-to-bob length in
// pixels): a metronome rises kHeightUnits above its board (box 2.6, needle 2.8 above the pivot,
// which is 1.5 above the board) and needs kSlotUnits of board (its needle swings ~2 u each side).
constexpr double kSlotUnits = 4.2;
constexpr double kHeightUnits = 5.6;  // metronome, board, rollers, and a deck above
// The platforms' largest excursion may take this fraction of the stage's width (less than the
// gap of 7% of a board's range on each side, where a ground spring's post stands).
constexpr double kMotionFraction = 0.05;

int depthOf(const Scene& s, int p) {
  int d = 0;
  for (int q = s.platforms[p].on; q >= 0 && d <= static_cast<int>(s.platforms.size());
       q = s.platforms[q].on)
    ++d;
  return d;
}

// Horizontal ranges: platforms on the floor share the stage's width; the platforms resting on one
// share its range.
void assignRanges(const Scene& s, int parent, double x0, double x1, std::vector<double>& lo,
                  std::vector<double>& hi) {
  std::vector<int> kids;
  for (int p = 0; p < static_cast<int>(s.platforms.size()); ++p)
    if (s.platforms[p].on == parent) kids.push_back(p);
  const double w = (x1 - x0) / std::max<std::size_t>(1, kids.size());
  for (std::size_t k = 0; k < kids.size(); ++k) {
    lo[kids[k]] = x0 + k * w;
    hi[kids[k]] = x0 + (k + 1) * w;
    assignRanges(s, kids[k], lo[kids[k]], hi[kids[k]], lo, hi);
  }
}

double longestPendulum(const Scene& s) {
  double l = 0.0;
  for (const SceneMetronome& m : s.metronomes) l = std::max(l, m.length_m);
  return l > 0 ? l : 1.0;
}

}  // namespace

SceneLayout layoutScene(const Scene& s) {
  SceneLayout lay;
  const double W = s.width, H = s.height, margin = 0.02 * H;
  lay.stage = {margin, 0.12 * H, 0.60 * W - margin, 0.80 * H};
  lay.traces = {0.66 * W, 0.14 * H, 0.32 * W, 0.56 * H};
  lay.floor_y = lay.stage.y + lay.stage.h;
  const int n_p = static_cast<int>(s.platforms.size());
  int levels = 1;
  for (int p = 0; p < n_p; ++p) levels = std::max(levels, depthOf(s, p) + 1);
  std::vector<double> lo(n_p, 0.0), hi(n_p, 0.0);
  assignRanges(s, -1, lay.stage.x, lay.stage.x + lay.stage.w, lo, hi);

  // the unit: every platform's metronomes fit their slots and their level's height
  const double level_h = lay.stage.h / levels;
  double u = level_h / kHeightUnits;
  for (int p = 0; p < n_p; ++p) {
    const std::size_t n = s.platforms[p].metronomes.size();
    if (n > 0) u = std::min(u, 0.86 * (hi[p] - lo[p]) / (n * kSlotUnits));
  }
  const double L = longestPendulum(s);
  lay.px_per_m = u / L;
  if (s.max_abs_x_m > 0)
    lay.px_per_m = std::min(lay.px_per_m, kMotionFraction * lay.stage.w / s.max_abs_x_m);
  lay.unit_px = lay.px_per_m * L;
  u = lay.unit_px;

  for (int p = 0; p < n_p; ++p) {
    SceneLayout::Board b;
    b.width = 0.86 * (hi[p] - lo[p]);
    b.left = lo[p] + 0.07 * (hi[p] - lo[p]);
    b.base_y = lay.floor_y - depthOf(s, p) * level_h;
    b.roller_r = std::max(2.0, 0.25 * u);
    b.thickness = std::max(3.0, 0.3 * u);
    b.top = b.base_y - 2 * b.roller_r - b.thickness;
    lay.boards.push_back(b);
  }
  lay.pivot_x.assign(s.metronomes.size(), 0.0);
  lay.pivot_y.assign(s.metronomes.size(), 0.0);
  lay.length_px.assign(s.metronomes.size(), 0.0);
  lay.platform_of.assign(s.metronomes.size(), 0);
  for (int p = 0; p < n_p; ++p) {
    const std::vector<int>& ms = s.platforms[p].metronomes;
    const double slot = lay.boards[p].width / std::max<std::size_t>(1, ms.size());
    for (std::size_t k = 0; k < ms.size(); ++k) {
      const int i = ms[k];
      lay.pivot_x[i] = lay.boards[p].left + (k + 0.5) * slot;
      lay.pivot_y[i] = lay.boards[p].top - 1.5 * u;
      lay.length_px[i] = lay.px_per_m * s.metronomes[i].length_m;
      lay.platform_of[i] = p;
    }
  }
  return lay;
}

}  // namespace metrosync::animation
