#include "sim/analysis/fit/fit_statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "base/number_text.h"
#include "sim/analysis/fit/difference_step.h"

namespace metrosync {

namespace {

// Columns from steps this many times smaller and larger agree with it to kSmoothAgreement where
// the model is smooth and nearly linear over that range; they do not past an escapement at
// grazing (a tick there or not: the difference jumps by the same amount whatever the step) or
// where a long record's late phase depends so strongly on the key that the cost has local minima
// a few 1e-4 apart (the benchmark's records of oscillator death, docs/bench/fit.md).
constexpr double kStepRatio = 10.0;
constexpr double kSmoothAgreement = 0.2;

// The longest prefix of the residuals over which columns a and b agree (cumulative norms, from
// the end: the residuals are in time order).
int agreeingRows(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::VectorXd diff2 = (a - b).cwiseAbs2(), ref2 = a.cwiseAbs2();
  double d = diff2.sum(), c = ref2.sum();
  int n = static_cast<int>(a.size());
  for (; n > 0 && !(d <= kSmoothAgreement * kSmoothAgreement * c); --n)
    d -= diff2(n - 1), c -= ref2(n - 1);
  return n;
}
// A Jacobian column this small against the largest is zero: the data do not see the key.
constexpr double kZeroColumn = 1e-10;
// A singular value of the unit-column Jacobian below this fraction of the largest is zero: two
// keys (or more) move the model alike to within one part in 1e6 (correlation 1 - 1e-12).
constexpr double kCollinear = 1e-6;
// A standard error this large against the key's own size determines nothing.
constexpr double kMaxRelativeError = 1.0;

}  // namespace

namespace {

// The central (or, where the model fails on one side, one-sided) difference of f in key j over
// h (in units of its scale) at values, r0 = f(values). False when the model fails on both sides.
bool difference(const ResidualFunction& f, const std::vector<double>& values,
                const std::vector<FreeParameter>& free, std::size_t j, double h,
                const Eigen::VectorXd& r0, Eigen::VectorXd& col) {
  const int m = static_cast<int>(r0.size());
  Eigen::VectorXd rp(m), rm(m);
  std::vector<double> vp = values, vm = values;
  vp[j] += h * free[j].scale;
  vm[j] -= h * free[j].scale;
  const bool plus = f(vp, rp.data());
  const bool minus = !(free[j].lower > vm[j]) && f(vm, rm.data());
  if (plus && minus)
    col = (rp - rm) / (2 * h);
  else if (plus)
    col = (rp - r0) / h;
  else if (minus)
    col = (r0 - rm) / h;
  return plus || minus;
}

// The difference step of key j (in units of its scale, difference_step.h) and its column `col`;
// sigma2: the residuals' mean square at `values`.
double linearStep(const ResidualFunction& f, const std::vector<double>& values,
                  const std::vector<FreeParameter>& free, std::size_t j, const Eigen::VectorXd& r0,
                  double sigma2, Eigen::VectorXd& col) {
  const double h0 = firstDifferenceStep(values[j] / free[j].scale);
  for (double h = h0;;) {
    if (!difference(f, values, free, j, h, r0, col))
      throw std::invalid_argument("the model fails on both sides of " + free[j].name);
    const double next =
        sigma2 > 0 ? shrunkDifferenceStep(h, h0, (col * h).squaredNorm() / sigma2) : 0.0;
    if (next == 0.0) return h;
    h = next;
  }
}

// The step the difference rule (difference_step.h) takes for a model linear in key j with the
// exact column `col` (in units of the key's scale)
double predictedStep(double x, const Eigen::VectorXd& col, double sigma2) {
  const double h0 = firstDifferenceStep(x);
  double h = h0;
  for (double next;
       sigma2 > 0 && (next = shrunkDifferenceStep(h, h0, (col * h).squaredNorm() / sigma2)) != 0.0;)
    h = next;
  return h;
}

// The model's own derivatives in units of the scales, and the prefix where each column agrees with
// the secant over kStepRatio of its difference step.
Linearization exactLinearization(const ResidualFunction& f, const JacobianFunction& jac, int m,
                                 const std::vector<double>& values,
                                 const std::vector<FreeParameter>& free, bool find_smooth) {
  Linearization lin;
  const int k = static_cast<int>(values.size());
  lin.r.resize(m);
  lin.J.resize(m, k);
  if (!jac(values, lin.r.data(), lin.J.data()))
    throw std::invalid_argument("the model fails at the optimum");
  lin.smooth_rows = m;
  const double sigma2 = lin.r.squaredNorm() / m;
  Eigen::VectorXd secant(m);
  for (int j = 0; j < k; ++j) {
    lin.J.col(j) *= free[j].scale;
    // a held key's column is not computed, an unseen one's is zero: no smoothness to check
    if (!find_smooth || lin.J.col(j).squaredNorm() == 0) continue;
    const double h = predictedStep(values[j] / free[j].scale, lin.J.col(j), sigma2);
    if (difference(f, values, free, j, kStepRatio * h, lin.r, secant))
      lin.smooth_rows = std::min(lin.smooth_rows, agreeingRows(lin.J.col(j), secant));
  }
  return lin;
}

}  // namespace

Linearization linearize(const ResidualFunction& f, int m, const std::vector<double>& values,
                        const std::vector<FreeParameter>& free, bool find_smooth,
                        const JacobianFunction& jac) {
  if (jac) return exactLinearization(f, jac, m, values, free, find_smooth);
  Linearization lin;
  lin.r.resize(m);
  lin.J.resize(m, static_cast<int>(values.size()));
  if (!f(values, lin.r.data())) throw std::invalid_argument("the model fails at the optimum");
  Eigen::VectorXd col(m), other(m);
  lin.smooth_rows = m;
  const double sigma2 = lin.r.squaredNorm() / m;
  for (std::size_t j = 0; j < values.size(); ++j) {
    const double h = linearStep(f, values, free, j, lin.r, sigma2, col);
    lin.J.col(static_cast<int>(j)) = col;
    for (const double step : {h / kStepRatio, h * kStepRatio})
      if (find_smooth && difference(f, values, free, j, step, lin.r, other))
        lin.smooth_rows = std::min(lin.smooth_rows, agreeingRows(col, other));
  }
  return lin;
}

std::vector<bool> unseenKeys(const Eigen::MatrixXd& J) {
  double largest = 0.0;
  for (int j = 0; j < J.cols(); ++j) largest = std::max(largest, J.col(j).norm());
  std::vector<bool> zero(J.cols());
  for (int j = 0; j < J.cols(); ++j) zero[j] = !(J.col(j).norm() > kZeroColumn * largest);
  return zero;
}

Uncertainty uncertainty(const Linearization& lin, const std::vector<double>& values,
                        const std::vector<FreeParameter>& free, const std::vector<bool>& held) {
  const std::size_t k = values.size();
  Uncertainty u;
  u.std_errors.resize(k);
  u.correlation.assign(k, std::vector<std::optional<double>>(k));
  std::vector<int> f;  // the keys fitted
  for (std::size_t j = 0; j < k; ++j)
    if (!held[j]) f.push_back(static_cast<int>(j));
  if (f.empty()) return u;
  // the rows over which the model is smooth: the rest would make the errors far too small
  const int n = static_cast<int>(f.size()), m = lin.smooth_rows;
  const std::vector<bool> unseen = unseenKeys(lin.J);
  for (int j : f)
    if (unseen[j]) return u.worst = j, u.why = "the data do not see it", u;
  Eigen::MatrixXd Jn(m, n);
  Eigen::VectorXd norm(n);
  for (int a = 0; a < n; ++a) {
    norm(a) = lin.J.col(f[a]).head(m).norm();
    if (!(norm(a) > 0))
      return u.worst = f[a], u.why = "the model is smooth in it only where it has no effect", u;
    Jn.col(a) = lin.J.col(f[a]).head(m) / norm(a);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Jn, Eigen::ComputeThinV);
  const Eigen::VectorXd s = svd.singularValues();
  for (int a = 0; a < n; ++a) u.singular_values.push_back(s(a));
  if (!(s(n - 1) > kCollinear * s(0))) {
    int lead = 0;
    svd.matrixV().col(n - 1).cwiseAbs().maxCoeff(&lead);
    u.worst = f[lead];
    u.why = "its effect on the model is a combination of the other keys' (singular value " +
            numberText(s(n - 1) / s(0), 2) + ")";
    return u;
  }
  u.sigma2 = lin.r.squaredNorm() / std::max(1, static_cast<int>(lin.r.size()) - n);
  // covariance of value / scale: D^-1 V S^-2 V^T D^-1
  const Eigen::MatrixXd V = svd.matrixV();
  const Eigen::MatrixXd cn = V * s.cwiseInverse().cwiseAbs2().asDiagonal() * V.transpose();
  double worst_ratio = kMaxRelativeError;
  for (int a = 0; a < n; ++a) {
    const int j = f[a];
    const double sd = std::sqrt(u.sigma2 * cn(a, a)) / norm(a) * free[j].scale;
    u.std_errors[j] = sd;
    for (int b = 0; b < n; ++b) u.correlation[j][f[b]] = cn(a, b) / std::sqrt(cn(a, a) * cn(b, b));
    const double size = std::max(std::abs(values[j]), free[j].size_floor);
    if (!(sd < worst_ratio * size)) {
      worst_ratio = size > 0 ? sd / size : HUGE_VAL;
      u.worst = j;
      u.why = "its standard error " + numberText(sd, 2) + " is not below its size " +
              numberText(size, 2);
    }
  }
  return u;
}

}  // namespace metrosync
