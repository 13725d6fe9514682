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
  return (sys.residual(x, p + h, region) - sys.residual(x, p - h, region)) / (2.0 * h);
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
