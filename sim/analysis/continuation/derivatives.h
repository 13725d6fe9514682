// Derivatives of a ContinuationSystem inside one region (its formulas held fixed) by central
// differences, and of a plain vector field (for the Lyapunov coefficient).
#pragma once

#include "sim/analysis/continuation/system.h"

namespace metrosync::continuation {

// dF/dx (n x n) and dF/dp (n x 1) by central differences, region held fixed.
Mat jacobianX(const ContinuationSystem& sys, const Vec& x, double p, const Region& region);
Vec derivativeP(const ContinuationSystem& sys, const Vec& x, double p, const Region& region);

// Jacobian (m x m) of a vector field f: R^m -> R^m by central differences.
Mat jacobianOf(const std::function<Vec(const Vec&)>& f, const Vec& y);

// Central-difference step for a coordinate of size |v|: balances the O(h^2) truncation against
// the O(eps / h) rounding of double precision (h ~ eps^(1/3) relative).
double centralStep(double v);

}  // namespace metrosync::continuation
