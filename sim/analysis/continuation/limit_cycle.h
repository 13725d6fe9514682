// The limit cycle born at a Hopf point of a smooth vector field y' = f(y, p), followed in p by
// multiple shooting (sim/analysis/continuation/shooting.h) with the phase condition
//   (y_0 - y_h) . d = 0       (y_0 on the hyperplane through the Hopf point orthogonal to the
//                              cycle's velocity there)
// continued by the pseudo-arclength core (arclength.h), outwards from the Hopf point only. The
// first cycle has a small amplitude a along the Hopf eigenvector (Newton on the arcs, T and p
// with the amplitude held, in units of a so that it stays well-conditioned as a -> 0). The branch
// stops where the period passes kMaxPeriodFactor times the Hopf period (a homoclinic orbit),
// where the orbit touches a border of the field's region (CycleField::margin: both located
// exactly, as borders of the continuation), at the range's end, or after s.max_points points.
// Stability: the Floquet multipliers, eigenvalues of the monodromy matrix (one is 1, the
// direction of the flow). Folds of cycles are the folds of this continuation (located: the
// parameter component of the tangent changes sign); period doublings and tori are changes of
// the multipliers between two points.
// For the slow flow, f is the reduced polar flow (SlowFlowProblem::polarRates) of the Hopf
// point's region: its periodic orbits are the metronomes' modulated (quasi-periodic) states.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sim/analysis/continuation/branch.h"
#include "sim/analysis/continuation/shooting.h"

namespace metrosync::continuation {

struct CyclePoint {
  double p = 0.0;
  double period = 0.0;
  Vec y0;                      // the cycle's point on the phase hyperplane
  Vec y_min, y_max;            // componentwise extremes over the orbit
  CVec multipliers;            // Floquet multipliers, the trivial one (~1) included
  double trivial_error = 0.0;  // distance of the multiplier nearest 1 from 1 (a check)
  bool stable = false;         // every other multiplier inside the unit circle
  std::vector<Vec> orbit;      // every integration step's end along the orbit
};

struct CycleBranch {
  double hopf_p = 0.0, hopf_frequency = 0.0;
  std::vector<CyclePoint> points;  // in order along the branch, from the Hopf point outwards
  std::string end;                 // why the branch stopped
  bool max_points = false;         // stopped by the point budget
  bool into_hopf = false;          // it ended shrinking onto a Hopf point (near its last point)
  std::vector<CyclePoint> folds;   // the folds of cycles, located
  // where the stability changes between consecutive points other than at a fold, in words (the
  // multiplier type: -1 period doubling, a complex pair Neimark-Sacker / torus)
  std::vector<std::string> changes;
};

// The cycle born at the Hopf point (y_h, p_h) of f (a pair +-i w of f_y there), over
// [s.p_min, s.p_max] (s.p_scale the parameter's unit in the arclength), at most s.max_points
// points. Throws std::runtime_error when there is no such pair or the first cycle does not
// converge.
CycleBranch continueCycleFromHopf(const CycleField& f, const Vec& y_h, double p_h,
                                  const ContinuationSettings& s);

// The branch stops where the period passes this multiple of the Hopf period (the period of a
// cycle approaching a homoclinic orbit grows without bound).
constexpr double kMaxPeriodFactor = 5.0;

}  // namespace metrosync::continuation
