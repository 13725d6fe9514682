// The bialternate product 2A (.) I of a square matrix A (k x k): a matrix of size k(k-1)/2 whose
// eigenvalues are lambda_i + lambda_j (i < j) for the eigenvalues lambda of A (Kuznetsov, Elements
// of Applied Bifurcation Theory, section 10.2.2). It is singular exactly where a pair of A's
// eigenvalues sums to zero: at a Hopf point (+-i w) or a neutral saddle (+-l), which makes it the
// defining function of Hopf curves (sim/analysis/continuation/fold_curve.h).
#pragma once

#include "sim/analysis/continuation/system.h"

namespace metrosync::continuation {

// Rows and columns indexed by the pairs (p, q), p > q, in the order (1,0), (2,0), (2,1), (3,0), ...
Mat bialternateProduct(const Mat& A);

}  // namespace metrosync::continuation
