#include "sim/analysis/fit/swings.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "base/constants.h"
#include "base/median.h"

namespace metrosync {

namespace {

// A crossing counts once the signal is this fraction of the last half-cycle's peak on the other
// side: noise of a few percent of the swing never makes two crossings out of one.
constexpr double kHysteresis = 0.2;
// Swings smaller than this many noise levels are not told apart from noise: the search stops.
constexpr double kMinPeakOverNoise = 5.0;
// Half-width of the fitting windows, in half-periods: Peak +-0.3 (phases 36..144 degrees from the
// crossing: clear of ticks at theta_c whenever the amplitude exceeds theta_c / sin 36 deg = 1.7
// theta_c, as a steady metronome's does), Crossing +-0.4 (inside the monotone half-cycle, whose
// ends are the extrema where the Coulomb centre jumps).
constexpr double kPeakHalfWidth = 0.3;
constexpr double kCrossingHalfWidth = 0.4;
// A window fit needs at least this many samples (3 unknowns and some to spare).
constexpr int kMinWindowSamples = 6;

// Noise level from second differences (an upper bound: the signal's own curvature adds to it).
double noiseLevel(const std::vector<double>& y) {
  std::vector<double> d;
  for (std::size_t i = 1; i + 1 < y.size(); ++i)
    d.push_back(std::abs(y[i + 1] - 2 * y[i] + y[i - 1]));
  return median(d) / (0.6745 * std::sqrt(6.0));
}

// Crossings of y (deviations from the centre) with hysteresis; time by linear interpolation at
// the last sign change before the signal got past the threshold.
std::vector<double> crossings(const std::vector<double>& t, const std::vector<double>& d) {
  std::vector<double> out;
  double peak = 0.0;
  for (double v : d) peak = std::max(peak, std::abs(v));
  const double floor = kMinPeakOverNoise * noiseLevel(d);
  double threshold = kHysteresis * peak, run_peak = 0.0;
  int side = 0;
  std::size_t last_change = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (i > 0 && (d[i] >= 0) != (d[i - 1] >= 0)) last_change = i;
    if (side == 0) {
      if (std::abs(d[i]) > threshold) side = d[i] > 0 ? 1 : -1;
      continue;
    }
    run_peak = std::max(run_peak, std::abs(d[i]));
    if (side * d[i] >= -threshold) continue;
    if (run_peak < floor) break;  // the swings have sunk into the noise
    const std::size_t j = last_change;
    out.push_back(t[j - 1] + (t[j] - t[j - 1]) * d[j - 1] / (d[j - 1] - d[j]));
    threshold = kHysteresis * run_peak;
    run_peak = 0.0;
    side = -side;
  }
  return out;
}

// Least-squares slope of crossing time against index, and its standard error.
void halfPeriod(const std::vector<double>& c, double& slope, double& error) {
  const double n = static_cast<double>(c.size());
  double mk = (n - 1) / 2, mt = 0.0;
  for (double v : c) mt += v / n;
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t k = 0; k < c.size(); ++k) {
    sxx += (k - mk) * (k - mk);
    sxy += (k - mk) * (c[k] - mt);
  }
  slope = sxy / sxx;
  error = 0.0;
  if (c.size() < 3) return;
  double ssr = 0.0;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const double r = c[k] - mt - slope * (k - mk);
    ssr += r * r;
  }
  error = std::sqrt(ssr / (n - 2) / sxx);
}

// A sinusoid a cos(s) + b sin(s) (+ c), s = w (t - t0), fitted to the samples in
// [t0 - hw, t0 + hw] (centre fixed at 0 when !free_centre): its amplitude (NaN with too few
// samples), where it crosses its own centre nearest t0 (for a crossing window), and the
// amplitude's standard error for unit noise on the samples.
struct WindowFit {
  double amplitude = std::nan("");
  double centre_crossing = 0.0;
  double error_per_noise = 0.0;
};
WindowFit windowFit(const std::vector<double>& t, const std::vector<double>& d, double t0,
                    double hw, double w, bool free_centre) {
  const auto lo = std::lower_bound(t.begin(), t.end(), t0 - hw) - t.begin();
  const auto hi = std::upper_bound(t.begin(), t.end(), t0 + hw) - t.begin();
  const int m = static_cast<int>(hi - lo), cols = free_centre ? 3 : 2;
  if (m < kMinWindowSamples) return {};
  Eigen::MatrixXd a(m, cols);
  Eigen::VectorXd b(m);
  for (int k = 0; k < m; ++k) {
    const double s = w * (t[lo + k] - t0);
    a(k, 0) = std::cos(s);
    a(k, 1) = std::sin(s);
    if (free_centre) a(k, 2) = 1.0;
    b(k) = d[lo + k];
  }
  const Eigen::VectorXd p = a.colPivHouseholderQr().solve(b);
  // the extremum is at s = atan2(b, a); the crossing a quarter period away, within (-pi/2, pi/2]
  double s = std::atan2(p(1), p(0)) + kPi / 2;
  s -= kPi * std::ceil(s / kPi - 0.5);
  const double amplitude = std::hypot(p(0), p(1));
  // the amplitude's gradient in (a, b) is u = (a, b) / amplitude: its variance u^T (A^T A)^-1 u
  Eigen::VectorXd u = Eigen::VectorXd::Zero(cols);
  if (amplitude > 0) u.head(2) << p(0) / amplitude, p(1) / amplitude;
  const double var = u.dot((a.transpose() * a).ldlt().solve(u));
  return {amplitude, t0 + s / w, std::sqrt(std::max(var, 0.0))};
}

// One fit per half-cycle: Peak windows halfway between crossings, Crossing windows at the
// crossings (inside the record by a full window); t_s of a Crossing swing is the fitted middle.
std::vector<Swing> fitWindows(const std::vector<double>& t, const std::vector<double>& v,
                              const std::vector<double>& c, double half, bool peak) {
  const double w = kPi / half, hw = (peak ? kPeakHalfWidth : kCrossingHalfWidth) * half;
  std::vector<Swing> out;
  for (std::size_t k = 0; k < c.size(); ++k) {
    if (peak && k + 1 >= c.size()) break;
    const double t0 = peak ? 0.5 * (c[k] + c[k + 1]) : c[k];
    if (!peak && (t0 - hw < t.front() || t0 + hw > t.back())) continue;
    const WindowFit f = windowFit(t, v, t0, hw, w, !peak);
    if (std::isfinite(f.amplitude))
      out.push_back({peak ? t0 : f.centre_crossing, f.amplitude, peak ? f.error_per_noise : 0.0});
  }
  return out;
}

}  // namespace

Swings findSwings(const std::vector<double>& t_s, const std::vector<double>& y,
                  SwingWindow window) {
  std::vector<double> t, v;
  for (std::size_t i = 0; i < y.size(); ++i)
    if (!std::isnan(y[i])) t.push_back(t_s[i]), v.push_back(y[i]);
  Swings out;
  if (v.size() < 3) return out;
  const double centre = median(v);
  for (double& x : v) x -= centre;
  out.crossings_s = crossings(t, v);
  const std::vector<double>& c = out.crossings_s;
  if (c.size() < 2) return out;
  halfPeriod(c, out.half_period_s, out.half_period_error_s);
  if (window == SwingWindow::Peak) {
    out.swings = fitWindows(t, v, c, out.half_period_s, true);
    return out;
  }
  // Crossing: the centre moves (Coulomb friction), so the median's crossings are off the
  // half-cycles' middles by an amount that grows as the swing shrinks; each window's own fit says
  // where its middle is: the period again from those, then the final fits there
  std::vector<double> middles;
  for (const Swing& sw : fitWindows(t, v, c, out.half_period_s, false)) middles.push_back(sw.t_s);
  if (middles.size() >= 2) {
    out.crossings_s = middles;
    halfPeriod(middles, out.half_period_s, out.half_period_error_s);
  }
  out.swings = fitWindows(t, v, out.crossings_s, out.half_period_s, false);
  return out;
}

}  // namespace metrosync
