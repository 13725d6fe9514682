// The limit cycle born at a Hopf point of a smooth vector field y' = f(y, p), followed in p by
// single shooting (Seydel, Practical Bifurcation and Stability Analysis, 7.3): unknowns a point
// y0 on the cycle and its period T,
//   phi(y0, T; p) - y0 = 0                 (it closes after one period)
//   (y0 - y_h) . d     = 0                 (phase: y0 on the hyperplane through the Hopf point
//                                           orthogonal to the cycle's velocity there)
// continued by the pseudo-arclength core (arclength.h). phi is the flow map by fixed-step
// Verner 7(6) with a fixed number of steps per period (so that it is a smooth function of T).
// The cycle starts at amplitude kStartAmplitude along the Hopf eigenvector (Newton on y0, T and p
// with the amplitude held), then grows both ways in p. Stability: the Floquet multipliers, the
// eigenvalues of the monodromy matrix d phi / d y0 (one is 1, the direction of the flow).
// For the slow flow, f is the reduced polar flow (SlowFlowProblem::polarRates) of the Hopf
// point's region: its periodic orbits are the metronomes' modulated (quasi-periodic) states.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sim/analysis/continuation/branch.h"

namespace metrosync::continuation {

struct CycleField {
  int n = 0;
  std::function<Vec(const Vec& y, double p)> rhs;
  // Whether (y, p) is still where rhs's formulas hold (a region of a piecewise-smooth field);
  // the branch ends where its orbit leaves. Empty: everywhere.
  std::function<bool(const Vec& y, double p)> inside;
};

struct CyclePoint {
  double p = 0.0;
  double period = 0.0;
  Vec y0;                      // the cycle's point on the phase hyperplane
  Vec y_min, y_max;            // componentwise extremes over the orbit
  CVec multipliers;            // Floquet multipliers, the trivial one (~1) included
  double trivial_error = 0.0;  // distance of the multiplier nearest 1 from 1 (a check)
  bool stable = false;         // every other multiplier inside the unit circle
};

struct CycleBranch {
  double hopf_p = 0.0, hopf_frequency = 0.0;
  std::vector<CyclePoint> points;  // in order along the branch, from the Hopf point outwards
  std::string end;                 // why the branch stopped
  // where the stability changes between consecutive points, in words (with the multiplier type:
  // +1 fold of cycles, -1 period doubling, complex pair Neimark-Sacker / torus)
  std::vector<std::string> changes;
};

// The cycle born at the Hopf point (y_h, p_h) of f (a pair +-i w of f_y there), over
// [s.p_min, s.p_max]. Throws std::runtime_error when there is no such pair or the first cycle
// does not converge.
CycleBranch continueCycleFromHopf(const CycleField& f, const Vec& y_h, double p_h,
                                  const ContinuationSettings& s);

// The shooting's fixed number of Verner 7(6) steps per period (limit_cycle.cpp says why).
constexpr int kCycleSteps = 200;

// The flow map phi(y0, T; p) with `steps` fixed steps; `orbit` (optional) receives every step's
// end.
Vec flowMap(const CycleField& f, const Vec& y0, double T, double p, int steps,
            std::vector<Vec>* orbit = nullptr);

}  // namespace metrosync::continuation
