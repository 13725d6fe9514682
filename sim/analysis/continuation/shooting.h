// Multiple shooting for the periodic orbits of a smooth vector field y' = f(y, p) (Seydel,
// Practical Bifurcation and Stability Analysis, 7.3; Keller): the period T is split into
// kSegments arcs of equal length, the unknowns are the arcs' starts y_0 .. y_{M-1} and T, and
//   phi(y_j, T / M; p) - y_{j+1} = 0      (j = 0 .. M-1, y_M = y_0: the arcs join and close)
// Each arc grows a perturbation only by the expansion over T / M, so cycles with a strongly
// unstable direction (a multiplier of 1e7 on the slow flow's saddle cycles), where single shooting
// over the whole period loses every digit, stay well-conditioned. phi is fixed-step Verner 7(6),
// kStepsPerArc steps per arc (a smooth function of y_j, T and p). The Jacobian is
// block-bidiagonal: d phi / d y_j by central differences (2 n arcs per segment: as cheap as one
// single-shooting Jacobian), d phi / d tau = f at the arc's end. The monodromy matrix is the
// product of the arcs' Jacobians.
#pragma once

#include <functional>
#include <vector>

#include "sim/analysis/continuation/system.h"

namespace metrosync::continuation {

struct CycleField {
  int n = 0;
  std::function<Vec(const Vec& y, double p)> rhs;
  // How far y lies inside the region where rhs's formulas hold (> 0 inside, 0 on its border:
  // a piecewise-smooth field); a cycle branch ends where its orbit touches a border. Empty:
  // everywhere.
  std::function<double(const Vec& y, double p)> margin;
};

constexpr int kSegments = 20;
// Verner 7(6) with 10 fixed steps per arc, 200 per period: local errors ~(T/200)^8, below 1e-11
// for the slow flow's periods (~5-30 in tau).
constexpr int kStepsPerArc = 10;

// The flow map phi(y0, T; p) with `steps` fixed steps; `orbit` (optional) receives every step's
// end.
Vec flowMap(const CycleField& f, const Vec& y0, double T, double p, int steps,
            std::vector<Vec>* orbit = nullptr);

// The cycle's unknowns u = (y_0, .., y_{M-1}, T): (M n + 1) x 1.
class MultipleShooting {
 public:
  explicit MultipleShooting(const CycleField& f) : f_(f) {}
  int size() const { return kSegments * f_.n + 1; }
  // phi(y_j, T / M) - y_{j+1}, (M n) x 1.
  Vec residual(const Vec& u, double p) const;
  // d residual / d u, (M n) x (M n + 1); the monodromy matrix when asked.
  Mat jacobian(const Vec& u, double p, Mat* monodromy = nullptr) const;
  // Every step's end along the orbit, M * kStepsPerArc states.
  std::vector<Vec> orbit(const Vec& u, double p) const;
  // u for the orbit y(t) sampled at the arcs' starts, t_j = j T / M.
  Vec sample(const std::function<Vec(double t)>& y, double T) const;
  // The smallest margin over the orbit (f.margin; +inf without one).
  double margin(const Vec& u, double p) const;

 private:
  const CycleField& f_;
};

}  // namespace metrosync::continuation
