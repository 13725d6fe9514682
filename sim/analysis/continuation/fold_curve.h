// Two-parameter continuation of a fold (limit point) of the slow flow's locked states: the curve in
// the (p1, p2) plane where the locked state is born or dies. The fold is the regular solution of
// the minimally augmented system (Govaerts, Numerical Methods for Bifurcations of Dynamical
// Equilibria, ch. 4)
//   F(x, p1; p2) = 0,   g(x, p1; p2) = 0,   with [F_x b; c^T 0] [v; g] = [0; 1],
// b and c the left and right null vectors of F_x at the starting fold (g = 0 exactly where F_x is
// singular), continued in p2 by the same pseudo-arclength core (arclength.h), inside the starting
// fold's region (the curve stops at a border).
#pragma once

#include <string>
#include <vector>

#include "sim/analysis/continuation/branch.h"
#include "sim/analysis/continuation/slow_flow_problem.h"

namespace metrosync::continuation {

// The slow flow's parameters at (p1, p2).
using ParamsAt2 = std::function<ScaledParams(double p1, double p2)>;

struct FoldCurvePoint {
  double p1 = 0.0, p2 = 0.0;
  std::vector<double> A, psi;  // the state at the fold
};

struct FoldCurve {
  std::vector<FoldCurvePoint> points;  // in order along the curve
  std::string end_backward, end_forward;
};

// From the fold (x, p1) found at p2 = p2_0 (region: its region), over p2 in [s.p_min, s.p_max].
FoldCurve continueFold(const ParamsAt2& params, int reference, const Vec& x, double p1, double p2_0,
                       const Region& region, const ContinuationSettings& s);

}  // namespace metrosync::continuation
