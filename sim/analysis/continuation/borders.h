// A branch reaching a border of its region (the escapement switching at A_i = theta_c, the
// platform's regime at s = 1 or s_b): the point is located exactly on the border with the old
// formulas, then the branch goes on with the other side's formulas.
//   kink (F continuous, its derivative not): the branch goes on from the same point, along the
//     new formulas' tangent into the new region; it may turn back in p there (a non-smooth fold);
//   jump (F itself jumps): the branch goes on along the border as border states
//     (sim/analysis/continuation/border_states.h) until it leaves the border into one side.
// Either way Border bifurcations are recorded, saying whether stability changes.
#pragma once

#include <optional>
#include <vector>

#include "sim/analysis/continuation/arclength.h"

namespace metrosync::continuation {

// `at` is on border k, with its old region, the last point of w. Returns the point the branch
// goes on from (new region), or nullopt when it ends (w.end says why); the points and special
// points in between are appended to w (at most max_points in w).
std::optional<BranchPoint> crossBorder(const ContinuationSystem& sys, const BranchPoint& at, int k,
                                       const ContinuationSettings& s, int max_points, Walk& w);

}  // namespace metrosync::continuation
