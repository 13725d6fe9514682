// Two-parameter continuation of a fold (limit point) or a Hopf point of the slow flow's locked
// states: the curve in the (p1, p2) plane where a locked state is born or dies (fold) or starts to
// oscillate (Hopf). Either is the regular solution of a minimally augmented system (Govaerts,
// Numerical Methods for Bifurcations of Dynamical Equilibria, ch. 4)
//   F(x, p1; p2) = 0,   g(x, p1; p2) = 0,   with [M b; c^T 0] [v; g] = [0; 1],
// where M is F_x for a fold and the bialternate product 2A (.) I of the reduced Jacobian A for a
// Hopf point (bialternate.h: singular where two eigenvalues sum to 0), b and c the left and right
// null vectors of M at the starting point (g = 0 exactly where M is singular), continued in p2 by
// the same pseudo-arclength core (arclength.h), inside the starting point's region (the curve
// stops at a border). A Hopf curve also stops where its pair of eigenvalues +-i w turns real (a
// Bogdanov-Takens point: beyond it the same equation describes a neutral saddle, not a Hopf point).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "sim/analysis/continuation/branch.h"
#include "sim/analysis/continuation/slow_flow_problem.h"

namespace metrosync::continuation {

// The slow flow's parameters at (p1, p2).
using ParamsAt2 = std::function<ScaledParams(double p1, double p2)>;

enum class CurveKind { Fold, Hopf };
const char* toString(CurveKind k);  // "fold", "hopf"

struct FoldCurvePoint {
  double p1 = 0.0, p2 = 0.0;
  std::vector<double> A, psi;  // the state at the point
  double frequency = 0.0;      // Hopf: w of the pair +-i w (slow-time angular frequency); fold: 0
};

struct FoldCurve {
  CurveKind kind = CurveKind::Fold;
  std::vector<FoldCurvePoint> points;  // in order along the curve
  std::string end_backward, end_forward;
  // a curve that could not be followed: its seed (the point found in the first key) and why
  double seed_p1 = 0.0, seed_p2 = 0.0;
  std::string failure;
};

// p1 held inside [lo, hi]: the curve ends where it leaves (a map's range, sweep --boundaries).
struct P1Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
};

// From the fold (x, p1) found at p2 = p2_0 (region: its region), over p2 in [s.p_min, s.p_max].
FoldCurve continueFold(const ParamsAt2& params, int reference, const Vec& x, double p1, double p2_0,
                       const Region& region, const ContinuationSettings& s, P1Range range = {});
// The same for a Hopf point (x, p1) found at p2 = p2_0.
FoldCurve continueHopf(const ParamsAt2& params, int reference, const Vec& x, double p1, double p2_0,
                       const Region& region, const ContinuationSettings& s, P1Range range = {});

}  // namespace metrosync::continuation
