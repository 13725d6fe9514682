#include "sim/analysis/continuation/derivatives.h"

#include <algorithm>
#include <cmath>

namespace metrosync::continuation {

Region regionAt(const ContinuationSystem& sys, const Vec& x, double p) {
  Region r;
  if (!sys.borders) return r;
  const Vec b = sys.borders(x, p);
  for (int k = 0; k < b.size(); ++k) r.push_back(b(k) > 0.0 ? 1 : 0);
  return r;
}

double centralStep(double v) {
  // eps^(1/3) ~ 6e-6: truncation h^2 and rounding eps / h are then both ~ 4e-11 (relative)
  constexpr double kRelativeStep = 6e-6;
  return kRelativeStep * std::max(1.0, std::abs(v));
}

Mat jacobianX(const ContinuationSystem& sys, const Vec& x, double p, const Region& region) {
  if (sys.jacobian) return sys.jacobian(x, p, region);
  Mat J(sys.n, sys.n);
  for (int j = 0; j < sys.n; ++j) {
    const double h = centralStep(x(j));
    Vec xp = x, xm = x;
    xp(j) += h;
    xm(j) -= h;
    J.col(j) = (sys.residual(xp, p, region) - sys.residual(xm, p, region)) / (2.0 * h);
  }
  return J;
}

Vec derivativeP(const ContinuationSystem& sys, const Vec& x, double p, const Region& region) {
  const double h = centralStep(p);
  const Vec up = sys.residual(x, p + h, region), down = sys.residual(x, p - h, region);
  if (up.allFinite() && down.allFinite()) return (up - down) / (2.0 * h);
  // p at the edge of its domain (mu = 0: F is not defined below): the one-sided second-order
  // difference from the side where it is
  const double d = up.allFinite() ? h : -h;
  const Vec f0 = sys.residual(x, p, region), f1 = up.allFinite() ? up : down;
  const Vec f2 = sys.residual(x, p + 2 * d, region);
  return (-3.0 * f0 + 4.0 * f1 - f2) / (2.0 * d);
}

Mat jacobianOf(const std::function<Vec(const Vec&)>& f, const Vec& y) {
  const int m = static_cast<int>(y.size());
  Mat J(m, m);
  for (int j = 0; j < m; ++j) {
    const double h = centralStep(y(j));
    Vec yp = y, ym = y;
    yp(j) += h;
    ym(j) -= h;
    J.col(j) = (f(yp) - f(ym)) / (2.0 * h);
  }
  return J;
}

}  // namespace metrosync::continuation
