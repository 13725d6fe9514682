// Newton's method for a ContinuationSystem inside one region: at a fixed parameter, and the
// pseudo-arclength corrector with its tangent.
#pragma once

#include <optional>

#include "sim/analysis/continuation/system.h"

namespace metrosync::continuation {

// Newton accepts a solution when max |F_i| < sys.tolerance, 1e-12 by default: the fixed points
// satisfy the slow flow to 1e-12 (the requirement), with room for the rounding of O(1)
// terms (~1e-16).

// Newton on F(x, p) = 0 at fixed p from x0; nullopt when it does not converge.
std::optional<Vec> solveAt(const ContinuationSystem& sys, const Vec& x0, double p,
                           const Region& region);

// A point (x, p) of a branch as one vector y = (x, p), (n + 1) x 1.
struct Corrected {
  Vec y;
  int iterations = 0;
  // [F_x F_p] at the last iterate but one (within the last Newton step of y); empty when the
  // predictor itself was accepted
  Mat extended;
};

// Pseudo-arclength corrector: F(y) = 0 and t0 . (y - y0) = h, from the predictor y0 + h t0.
std::optional<Corrected> correct(const ContinuationSystem& sys, const Vec& y0, const Vec& t0,
                                 double h, const Region& region);

// Unit tangent of the branch at y, oriented along `ref` (t . ref > 0): the kernel of [F_x F_p].
Vec tangentAt(const ContinuationSystem& sys, const Vec& y, const Vec& ref, const Region& region);

// The same from [F_x F_p] given.
Vec tangentOf(const Mat& extended, const Vec& ref);

// [F_x F_p] at y, n x (n + 1).
Mat extendedJacobian(const ContinuationSystem& sys, const Vec& y, const Region& region);

}  // namespace metrosync::continuation
