#include "sim/analysis/fit/noise_level.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "base/median.h"

namespace metrosync {

namespace {

// Local polynomial: degree 4 over 7 samples (a swing sampled 30 times a period leaves ~1e-5 rad)
constexpr int kDegree = 4;
constexpr int kHalfWidth = 3;
constexpr int kCheckHalfWidth = 4;  // the second estimate
// The two estimates agree to this ratio on white noise (their scatter is a few percent with the
// thousands of windows of a record); beyond it the signal leaks into the residuals.
constexpr double kAgreement = 1.15;
// Fewer windows than this give no estimate worth the name.
constexpr int kMinWindows = 30;
// The median of |N(0, 1)|.
constexpr double kMadToSigma = 1.0 / 0.6744897501960817;

// The normalized residual at the middle of the window t[i - h .. i + h] (times relative to t[i]).
double middleResidual(const std::vector<double>& t, const std::vector<double>& y, std::size_t i,
                      int h) {
  const int n = 2 * h + 1;
  const double span = t[i + h] - t[i - h];
  Eigen::MatrixXd V(n, kDegree + 1);
  Eigen::VectorXd b(n);
  for (int k = 0; k < n; ++k) {
    const double s = (t[i - h + k] - t[i]) / span;
    double p = 1.0;
    for (int d = 0; d <= kDegree; ++d, p *= s) V(k, d) = p;
    b(k) = y[i - h + k];
  }
  const Eigen::MatrixXd A = V.transpose() * V;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(A);
  const Eigen::VectorXd coef = ldlt.solve(V.transpose() * b);
  const Eigen::VectorXd vm = V.row(h).transpose();
  const double leverage = vm.dot(ldlt.solve(vm));
  return (b(h) - vm.dot(coef)) / std::sqrt(std::max(1.0 - leverage, 1e-12));
}

// sigma from every window of 2h + 1 present samples that holds no tick
NoiseEstimate estimateWith(const std::vector<double>& t, const std::vector<double>& y,
                           const std::vector<bool>& kink, int h) {
  std::vector<int> kinks_before(t.size() + 1, 0);  // prefix count of kinks
  for (std::size_t i = 0; i < t.size(); ++i) kinks_before[i + 1] = kinks_before[i] + kink[i];
  std::vector<double> r;
  for (std::size_t i = h; i + h < t.size(); ++i) {
    if (kinks_before[i + h] - kinks_before[i - h] > 0) continue;  // a tick inside
    r.push_back(std::abs(middleResidual(t, y, i, h)));
  }
  NoiseEstimate e;
  e.windows = static_cast<int>(r.size());
  if (e.windows >= kMinWindows) e.sigma = kMadToSigma * median(r);
  return e;
}

}  // namespace

std::vector<bool> escapementTicks(const MeasuredData& data,
                                  const std::vector<double>& theta_c_rad) {
  std::vector<bool> ticks(data.t_s.size(), false);
  for (const DataColumn& c : data.columns) {
    if (c.metronome < 0 || c.metronome >= static_cast<int>(theta_c_rad.size())) continue;
    const double tc = theta_c_rad[c.metronome];
    // between two present samples (missing ones skipped: the tick is then anywhere in the gap)
    std::size_t prev = data.t_s.size();
    for (std::size_t i = 0; i < data.t_s.size(); ++i) {
      if (std::isnan(c.values[i])) continue;
      if (prev < data.t_s.size()) {
        const double a = c.values[prev], b = c.values[i];
        // up through +theta_c, or down through -theta_c: where the escapement ticks
        if ((a < tc && b >= tc) || (a > -tc && b <= -tc))
          for (std::size_t k = prev; k < i; ++k) ticks[k] = true;
      }
      prev = i;
    }
  }
  return ticks;
}

NoiseEstimate estimateNoise(const MeasuredData& data, const DataColumn& column,
                            const std::vector<bool>& ticks) {
  std::vector<double> t, y;
  std::vector<bool> kink;  // between this present sample and the next
  std::size_t prev = data.t_s.size();
  for (std::size_t i = 0; i < data.t_s.size(); ++i) {
    if (std::isnan(column.values[i])) continue;
    if (prev < i)  // a tick anywhere between the two present samples
      for (std::size_t k = prev; k < i; ++k) kink.back() = kink.back() || ticks[k];
    t.push_back(data.t_s[i]);
    y.push_back(column.values[i]);
    kink.push_back(false);
    prev = i;
  }
  NoiseEstimate e = estimateWith(t, y, kink, kHalfWidth);
  const NoiseEstimate check = estimateWith(t, y, kink, kCheckHalfWidth);
  e.reliable = e.sigma > 0 && check.sigma > 0 && check.sigma < kAgreement * e.sigma &&
               e.sigma < kAgreement * check.sigma;
  if (e.sigma == 0) {  // ticks in nearly every window (a coarse record): an upper bound from all
    e = estimateWith(t, y, std::vector<bool>(t.size(), false), kHalfWidth);
    e.reliable = false;
  }
  return e;
}

}  // namespace metrosync
