#include "sim/analysis/continuation/newton.h"

#include <cmath>

#include "sim/analysis/continuation/derivatives.h"

namespace metrosync::continuation {

namespace {

// Newton iterations before giving up: converging runs need 3-6 from a predictor; more means the
// predictor was too far (the step control then halves the step).
constexpr int kMaxIterations = 12;

bool finite(const Vec& v) {
  return v.allFinite();
}

// Newton polishes to an eighth of the acceptance level (sys.tolerance) so that every component,
// and the modulus of each complex equation, is safely below it; it accepts the acceptance level
// once the steps reach rounding (a residual of O(1) terms cannot go lower).
constexpr double kPolishFraction = 1.0 / 8;
constexpr double kRoundingStep = 1e-14;

bool converged(const ContinuationSystem& sys, double residual, double step, double size) {
  return residual < kPolishFraction * sys.tolerance ||
         (residual < sys.tolerance && step < kRoundingStep * (1 + size));
}

// A Jacobian with a smaller pivot than this (relative to the largest) is singular: a continuum of
// solutions through x (a neutral family, sim/analysis/continuation/family.h) rather than an
// isolated one; the difference Jacobian's own noise is ~1e-10.
constexpr double kSingularPivot = 1e-9;

// -J^-1 F, or the least-squares step of least norm where J is singular (Newton then converges to
// the nearest member of a continuum of solutions).
Vec newtonStep(const Mat& J, const Vec& F) {
  Eigen::FullPivLU<Mat> lu(J);
  lu.setThreshold(kSingularPivot);
  if (lu.isInvertible()) return lu.solve(-F);
  return J.completeOrthogonalDecomposition().solve(-F);
}

}  // namespace

Mat extendedJacobian(const ContinuationSystem& sys, const Vec& y, const Region& region) {
  const Vec x = y.head(sys.n);
  const double p = y(sys.n);
  Mat M(sys.n, sys.n + 1);
  M.leftCols(sys.n) = jacobianX(sys, x, p, region);
  M.col(sys.n) = derivativeP(sys, x, p, region);
  return M;
}

std::optional<Vec> solveAt(const ContinuationSystem& sys, const Vec& x0, double p,
                           const Region& region) {
  Vec x = x0;
  for (int it = 0; it < 2 * kMaxIterations; ++it) {
    const Vec F = sys.residual(x, p, region);
    if (!finite(F)) return std::nullopt;
    const double r = F.lpNorm<Eigen::Infinity>();
    if (r < kPolishFraction * sys.tolerance) return x;
    const Vec dx = newtonStep(jacobianX(sys, x, p, region), F);
    if (!finite(dx)) return std::nullopt;
    if (converged(sys, r, dx.norm(), x.norm())) return x;
    x += dx;
  }
  return std::nullopt;
}

std::optional<Corrected> correct(const ContinuationSystem& sys, const Vec& y0, const Vec& t0,
                                 double h, const Region& region) {
  const int n = sys.n;
  Vec y = y0 + h * t0;
  Mat M(n + 1, n + 1);
  for (int it = 1; it <= kMaxIterations; ++it) {
    Vec G(n + 1);
    G.head(n) = sys.residual(y.head(n), y(n), region);
    G(n) = t0.dot(y - y0) - h;
    if (!finite(G)) return std::nullopt;
    const double r = G.lpNorm<Eigen::Infinity>();
    if (r < kPolishFraction * sys.tolerance) return Corrected{y, it, it > 1 ? M.topRows(n) : Mat()};
    M.topRows(n) = extendedJacobian(sys, y, region);
    M.row(n) = t0.transpose();
    const Vec dy = M.fullPivLu().solve(-G);
    if (!finite(dy)) return std::nullopt;
    if (converged(sys, r, dy.norm(), y.norm())) return Corrected{y, it, M.topRows(n)};
    y += dy;
  }
  return std::nullopt;
}

Vec tangentAt(const ContinuationSystem& sys, const Vec& y, const Vec& ref, const Region& region) {
  return tangentOf(extendedJacobian(sys, y, region), ref);
}

Vec tangentOf(const Mat& extended, const Vec& ref) {
  const int n = static_cast<int>(extended.rows());
  Mat M(n + 1, n + 1);
  M.topRows(n) = extended;
  M.row(n) = ref.transpose();
  Vec rhs = Vec::Zero(n + 1);
  rhs(n) = 1.0;
  Vec t = M.fullPivLu().solve(rhs);
  t.normalize();
  if (t.dot(ref) < 0) t = -t;
  return t;
}

}  // namespace metrosync::continuation
