#include "sim/analysis/continuation/parameter_scale.h"

#include <cmath>

namespace metrosync::continuation {

ParameterScale::ParameterScale(double p0, const ContinuationSettings& s)
    : p0_(p0), scale_(s.p_scale), p_min_(s.p_min), p_max_(s.p_max) {
  q_min_ = q(p_min_);
  q_max_ = q(p_max_);
}

double ParameterScale::p(double q) const {
  if (q == q_min_) return p_min_;
  if (q == q_max_) return p_max_;
  return q == 0.0 ? p0_ : p0_ + scale_ * q;
}

double ParameterScale::q(double p) const {
  return (p - p0_) / scale_;
}

ContinuationSystem ParameterScale::system(const ContinuationSystem& sys) const {
  ContinuationSystem out = sys;
  const ParameterScale m = *this;
  out.residual = [sys, m](const Vec& x, double q, const Region& r) {
    return sys.residual(x, m.p(q), r);
  };
  if (sys.jacobian)
    out.jacobian = [sys, m](const Vec& x, double q, const Region& r) {
      return sys.jacobian(x, m.p(q), r);
    };
  if (sys.borders)
    out.borders = [sys, m](const Vec& x, double q) { return sys.borders(x, m.p(q)); };
  out.eigenvalues = [sys, m](const Vec& x, double q, const Region& r) {
    return sys.eigenvalues(x, m.p(q), r);
  };
  if (sys.lyapunov)
    out.lyapunov = [sys, m](const Vec& x, double q, const Region& r) {
      return sys.lyapunov(x, m.p(q), r);
    };
  // stop and accepted see (x, q): they do not use the parameter's value
  if (sys.stableOnBorder)
    out.stableOnBorder = [sys, m](const Vec& x, double q) { return sys.stableOnBorder(x, m.p(q)); };
  return out;
}

ContinuationSettings ParameterScale::settings(const ContinuationSettings& s) const {
  ContinuationSettings out = s;
  out.p_min = q_min_;
  out.p_max = q_max_;
  out.p_scale = 1.0;
  return out;
}

void ParameterScale::restore(BranchPoint& b) const {
  const int n = static_cast<int>(b.y.size()) - 1;
  b.y(n) = p(b.y(n));
  b.tangent(n) *= scale_;
  b.tangent.normalize();
}

void ParameterScale::restore(Branch& b) const {
  for (BranchPoint& q : b.points) restore(q);
  for (Bifurcation& e : b.special) restore(e.point);
  if (!std::isnan(b.end_p_backward)) b.end_p_backward = p(b.end_p_backward);
  if (!std::isnan(b.end_p_forward)) b.end_p_forward = p(b.end_p_forward);
}

}  // namespace metrosync::continuation
