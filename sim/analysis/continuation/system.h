// The problem a continuation follows: n equations F(x, p) = 0 in n unknowns x and one parameter p,
// piecewise smooth. The state space is cut by border functions b_k(x, p) (k = 0..K-1); a region
// is the side of each border (side_k = b_k > 0), and inside one region F has one smooth formula,
// which can be evaluated beyond the region's borders ("continued"). Derivatives are taken with the
// region held fixed, never across a border (sim/analysis/continuation/derivatives.h).
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

namespace metrosync::continuation {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;
using CVec = Eigen::VectorXcd;

// Side of each border: 1 where b_k > 0, 0 otherwise.
using Region = std::vector<int>;

struct ContinuationSystem {
  int n = 0;  // unknowns = equations; the parameter comes on top
  // F(x, p) with the formulas of `region`, continued beyond its borders.
  std::function<Vec(const Vec& x, double p, const Region& region)> residual;
  // b_k(x, p), (K x 1); empty for a smooth system.
  std::function<Vec(const Vec& x, double p)> borders;
  // Border k is a jump of F (not only a kink): the branch cannot go on continuously across it.
  std::function<bool(int k)> jumps;
  // dF/dx (n x n) with the formulas of `region` (optional: central differences of residual
  // otherwise; a system with structure, e.g. multiple shooting's block-bidiagonal Jacobian, gives
  // it much more cheaply).
  std::function<Mat(const Vec& x, double p, const Region& region)> jacobian;
  // Whether to watch for branch points (det [F_x F_p; t^T], a Jacobian per step).
  bool branch_points = true;
  // Whether to watch for special points at all (folds, branch and Hopf points): a walk that only
  // traces its points (a neutral family's members, family.h) needs none.
  bool special_points = true;
  // A stop rule on each step from y (accepted) to y_next (not yet): a reason ends the walk at y
  // (e.g. a limit cycle shrinking through zero amplitude within the step). Empty: none.
  std::function<std::string(const Vec& y, const Vec& y_next)> stop;
  // Called with each point the walk goes on from (y = (x, p)): a system whose equations follow
  // the branch (a limit cycle's phase condition through the last cycle) updates them here; the
  // point itself must still solve them.
  std::function<void(const Vec& y)> accepted;
  // Stability eigenvalues at a solution, formulas of `region` (the symmetry's zero removed).
  std::function<CVec(const Vec& x, double p, const Region& region)> eigenvalues;
  // First Lyapunov coefficient at a Hopf point (optional; NaN when unavailable).
  std::function<double(const Vec& x, double p, const Region& region)> lyapunov;
  // Name of border k, for messages ("A_2 = theta_c", "s = 1").
  std::function<std::string(int k)> borderName;
  // Border k ends a walk where the branch reaches it (the caller goes on with another system: a
  // segment of border states leaving the border, sim/analysis/continuation/border_states.h).
  // Empty: no border does.
  std::function<bool(int k)> exits;
  // Whether a state on a jump border (a fixed point of the two sides' formulas combined) is
  // stable, decided by the system's own dynamics (the slow flow integrated from beside it);
  // empty: unknown (sim/analysis/continuation/border_states.h).
  std::function<bool(const Vec& x, double p)> stableOnBorder;
  // Newton accepts a solution when max |F_i| is below this: 1e-12 (the slow flow's fixed points
  // to 1e-12, the requirement) unless the residual itself is noisier, e.g. built from a
  // difference Jacobian (fold_curve.cpp).
  double tolerance = 1e-12;
};

// The region of (x, p): the side of every border.
Region regionAt(const ContinuationSystem& sys, const Vec& x, double p);

}  // namespace metrosync::continuation
