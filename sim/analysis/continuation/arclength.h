// Pseudo-arclength continuation of a ContinuationSystem (Keller): predictor along the tangent,
// Newton corrector on F = 0 and t . (y - y0) = h, step control, both directions from the start.
// Along the way it watches test functions and locates their zeros on the branch (Illinois
// regula falsi in the arclength of the step):
//   fold     the parameter component of the tangent, t_p
//   branch   det [F_x F_p; t^T] (changes sign at a simple branch point, not at a fold)
//   Hopf     prod_{i<j} (lambda_i + lambda_j) (bialternate product: a complex pair crossing the
//            imaginary axis; a neutral saddle also zeroes it and is dropped)
//   border   b_k(x, p) evaluated with the old region's formulas; there the region switches and
//            the branch goes on with the other formula (kink), or is re-solved with it at the same
//            parameter (jump) when the border is a jump of F.
#pragma once

#include "sim/analysis/continuation/branch.h"

namespace metrosync::continuation {

// The branch through the solution (x0, p0), followed both ways; branch points found on it start
// new branches (switching onto the second kernel direction), up to settings.max_branches.
// Throws std::runtime_error when x0 does not converge at p0.
std::vector<Branch> continueFrom(const ContinuationSystem& sys, const Vec& x0, double p0,
                                 const ContinuationSettings& settings);

// A branch point at y with the region's formulas and its stability.
BranchPoint makePoint(const ContinuationSystem& sys, const Vec& y, const Vec& tangent,
                      const Region& region);

}  // namespace metrosync::continuation
