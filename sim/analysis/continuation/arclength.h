// Pseudo-arclength continuation of a ContinuationSystem (Keller): predictor along the tangent,
// Newton corrector on F = 0 and t . (y - y0) = h, step control (grown after an easy corrector,
// halved after a failure or a turn of the tangent by more than kMaxTurn), both directions from
// the start; the end of the parameter range is landed on exactly (Newton at p = the bound).
// Along the way it watches test functions and locates their zeros on the branch (Illinois
// regula falsi in the arclength of the step):
//   fold     the parameter component of the tangent, t_p
//   branch   det [F_x F_p; t^T] (changes sign at a simple branch point, not at a fold)
//   Hopf     prod_{i<j} (lambda_i + lambda_j) (bialternate product: a complex pair crossing the
//            imaginary axis; a neutral saddle also zeroes it and is dropped)
//   border   b_k(x, p) evaluated with the old region's formulas; there the region switches and
//            the branch goes on with the other formula (kink), or along the border as border
//            states (jump, sim/analysis/continuation/border_states.h).
#pragma once

#include "sim/analysis/continuation/branch.h"
#include "sim/analysis/continuation/smooth_events.h"

namespace metrosync::continuation {

// The branch through the solution (x0, p0), followed both ways; branch points found on it start
// new branches (switching onto the second kernel direction), up to settings.max_branches.
// Throws std::runtime_error when x0 does not converge at p0.
std::vector<Branch> continueFrom(const ContinuationSystem& sys, const Vec& x0, double p0,
                                 const ContinuationSettings& settings);

// A branch point at y with the region's formulas and its stability.
BranchPoint makePoint(const ContinuationSystem& sys, const Vec& y, const Vec& tangent,
                      const Region& region);

// One direction of a branch from `start` (its tangent oriented along the direction), in the
// system's own parameter (settings.p_scale is applied by continueFrom, not here).
struct Walk {
  std::vector<BranchPoint> points;  // from start on
  std::vector<Bifurcation> special;
  std::vector<BranchSwitch> switches;
  std::string end;          // why it stopped
  int exit = -1;            // the border (sys.exits) it stopped at, the last point on it; -1: none
  bool max_points = false;  // stopped by the point budget
  // the parameter where it stopped when `end` ends with " at p = " (its value is added by
  // continueFrom, in the caller's parameter); NaN otherwise
  double end_p = std::numeric_limits<double>::quiet_NaN();
};
Walk walkFrom(const ContinuationSystem& sys, const BranchPoint& start,
              const ContinuationSettings& s, int max_points);

}  // namespace metrosync::continuation
