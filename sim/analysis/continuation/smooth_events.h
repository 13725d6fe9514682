// The smooth bifurcations on one step of a branch (inside one region): folds, Hopf points and
// branch points, each located on the step; and the switch onto the second branch at a branch
// point.
#pragma once

#include <optional>
#include <vector>

#include "sim/analysis/continuation/branch.h"

namespace metrosync::continuation {

// Where a new branch leaves: the branch point and the kernel direction across the old branch.
struct BranchSwitch {
  BranchPoint at;
  Vec direction;  // unit, (n + 1) x 1, orthogonal to the old branch's tangent
};

// Looks for sign changes of the test functions between a and b (b the point at arclength h from
// a, same region) and appends the located points, in order of arclength, to `special`; each
// branch point also to `switches`.
void smoothEvents(const ContinuationSystem& sys, const BranchPoint& a, const BranchPoint& b,
                  double h, std::vector<Bifurcation>& special, std::vector<BranchSwitch>& switches);

// The start of the new branch: the branch point with the switch direction as its tangent, when a
// corrector step of arclength h along that direction converges; else nullopt.
std::optional<BranchPoint> switchBranch(const ContinuationSystem& sys, const BranchSwitch& sw,
                                        double h);

}  // namespace metrosync::continuation
