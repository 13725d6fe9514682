// The test functions of the continuation (sim/analysis/continuation/arclength.h) and the location
// of their zeros along one step.
#pragma once

#include <functional>
#include <optional>

#include "sim/analysis/continuation/branch.h"

namespace metrosync::continuation {

// Fold: the parameter component of the unit tangent.
double foldTest(const BranchPoint& q);
// Branch point: det [F_x F_p; t^T].
double branchTest(const ContinuationSystem& sys, const BranchPoint& q);
// Hopf: the sign of Re prod_{i<j} (lambda_i + lambda_j), scaled to stay finite for many
// eigenvalues (the M-th root of the product's modulus, M factors); 1 for fewer than two.
double hopfTest(const CVec& eigenvalues);

// The point at arclength h along the step from `from` (predictor along from.tangent, corrector,
// region held); iterations = the corrector's.
std::optional<BranchPoint> pointAlong(const ContinuationSystem& sys, const BranchPoint& from,
                                      double h, int* iterations = nullptr);

// The zero of g on the step (0, h1] from `from`, where g(from) = g0 and g(point at h1) = g1 have
// opposite signs (Illinois regula falsi on h); h_found is its arclength.
std::optional<BranchPoint> locateOnStep(const ContinuationSystem& sys, const BranchPoint& from,
                                        double h1, double g0, double g1,
                                        const std::function<double(const BranchPoint&)>& g,
                                        double* h_found = nullptr);

}  // namespace metrosync::continuation
