// A branch reaching a border of its region (the escapement switching at A_i = theta_c, the
// platform's regime at s = 1 or s_b): the point is located exactly on the border with the old
// formulas, then the branch goes on with the other side's formulas.
//   kink (F continuous, its derivative not): the branch goes on from the same point, along the
//     new formulas' tangent into the new region; it may turn back in p there (a non-smooth fold);
//   jump (F itself jumps): the other formulas are solved by Newton at the same parameter from the
//     border point; the branch goes on from that solution if it lies in the new region, else it
//     ends at the border (a boundary equilibrium).
// Either way a Border bifurcation is recorded, saying whether stability changes.
#pragma once

#include <optional>
#include <vector>

#include "sim/analysis/continuation/branch.h"

namespace metrosync::continuation {

// `at` is on border k, with its old region. Returns the point the branch goes on from (new
// region), or nullopt when it ends there (the recorded bifurcation's detail says why).
std::optional<BranchPoint> crossBorder(const ContinuationSystem& sys, const BranchPoint& at, int k,
                                       std::vector<Bifurcation>& special);

}  // namespace metrosync::continuation
