#include "sim/analysis/continuation/borders.h"

#include <cmath>

#include "sim/analysis/continuation/arclength.h"
#include "sim/analysis/continuation/border_states.h"
#include "sim/analysis/continuation/derivatives.h"
#include "sim/analysis/continuation/newton.h"

namespace metrosync::continuation {

namespace {

std::string stabilityWords(const BranchPoint& before, const BranchPoint& after) {
  const auto word = [](bool s) { return s ? "stable" : "unstable"; };
  if (before.stable == after.stable)
    return std::string("stability does not change (") + word(before.stable) + ")";
  return std::string("stability changes: ") + word(before.stable) + " -> " + word(after.stable);
}

// The kink: the same point, the new formulas' tangent pointing into the new region.
std::optional<BranchPoint> acrossKink(const ContinuationSystem& sys, const BranchPoint& at, int k,
                                      const Region& side, Bifurcation& b) {
  Vec t = tangentAt(sys, at.y, at.tangent, side);
  const double h = centralStep(1.0);
  auto border = [&](const Vec& y) { return sys.borders(y.head(sys.n), y(sys.n))(k); };
  const double slope = border(at.y + h * t) - border(at.y - h * t);
  if ((slope > 0) != (side[k] == 1)) t = -t;
  BranchPoint after = makePoint(sys, at.y, t, side);
  b.stability_changes = at.stable != after.stable;
  const bool turns = (t(sys.n) > 0) != (at.tangent(sys.n) > 0);
  b.detail = "kink of the vector field at " + sys.borderName(k) + ": " + stabilityWords(at, after) +
             (turns ? "; the branch turns back in the parameter here (non-smooth fold)" : "");
  return after;
}

}  // namespace

std::optional<BranchPoint> crossBorder(const ContinuationSystem& sys, const BranchPoint& at, int k,
                                       const ContinuationSettings& s, int max_points, Walk& w) {
  if (sys.jumps && sys.jumps(k)) return slideAlong(sys, at, k, s, max_points, w);
  Region side = at.region;
  side[k] = 1 - side[k];
  Bifurcation b;
  b.type = BifurcationType::Border;
  b.point = at;
  b.border = k;
  const auto after = acrossKink(sys, at, k, side, b);
  w.special.push_back(b);
  return after;
}

}  // namespace metrosync::continuation
