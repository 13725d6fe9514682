// A branch reaching a jump border k (where F itself jumps: the escapement's phase term at
// A_i = theta_c) at a boundary equilibrium goes on along the border, as border states: the states
// on b_k = 0 where the combination
//   w F_+(x, p) + (1 - w) F_-(x, p) = 0,      w in [0, 1]
// vanishes (F_+ the formulas of the border's positive side; Filippov's convex combination: in the
// slow flow, the escapement of the metronome at its threshold works on a fraction w of its
// swings). Unknowns (x, w), equations (the combination, b_k), continued in p by the same core
// (arclength.h) until w reaches 1 or 0 -- there the branch leaves the border into that side's
// region and goes on as a regular branch -- or the range ends. Their stability is not an
// eigenvalue problem (the vector field jumps across the border): ContinuationSystem's
// stableOnBorder decides it with the system's own dynamics, at every point of the segment.
#pragma once

#include <optional>

#include "sim/analysis/continuation/arclength.h"

namespace metrosync::continuation {

// Follows the border states from `at` (on border k, reached from the side at.region[k]) and
// appends their points and special points to w (at most max_points in w in all). Returns the
// point where the branch leaves the border, in sys with its new region and the tangent into it;
// nullopt when the walk ends on the border (w.end says why).
std::optional<BranchPoint> slideAlong(const ContinuationSystem& sys, const BranchPoint& at, int k,
                                      const ContinuationSettings& s, int max_points, Walk& w);

}  // namespace metrosync::continuation
