#include "sim/analysis/fit/section3.h"

#include <cmath>
#include <stdexcept>

#include "base/constants.h"
#include "models/scaling.h"
#include "sim/analysis/fit/swings.h"

namespace metrosync {

namespace {

constexpr int kMinSwings = 3;
// Relative step of the finite differences that carry errors through eq. J_estimate.
constexpr double kPropagationStep = 1e-6;

// Weighted least-squares line y = a + b t: slope b and its standard error (residual-based).
struct Line {
  double intercept = 0.0, slope = 0.0, slope_error = 0.0;
};
Line fitLine(const std::vector<double>& t, const std::vector<double>& y,
             const std::vector<double>& w) {
  double sw = 0.0, st = 0.0, sy = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) sw += w[k], st += w[k] * t[k], sy += w[k] * y[k];
  const double mt = st / sw, my = sy / sw;
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k)
    sxx += w[k] * (t[k] - mt) * (t[k] - mt), sxy += w[k] * (t[k] - mt) * (y[k] - my);
  Line l;
  l.slope = sxy / sxx;
  l.intercept = my - l.slope * mt;
  double ssr = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double r = y[k] - l.intercept - l.slope * t[k];
    ssr += w[k] * r * r;
  }
  const double n = static_cast<double>(t.size());
  l.slope_error = n > 2 ? std::sqrt(ssr / (n - 2) / sxx) : 0.0;
  return l;
}

Swings enoughSwings(const std::vector<double>& t_s, const std::vector<double>& y, SwingWindow w,
                    const char* what) {
  Swings s = findSwings(t_s, y, w);
  if (static_cast<int>(s.swings.size()) < kMinSwings)
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(s.swings.size()) +
                                " swings found, at least " + std::to_string(kMinSwings) +
                                " are needed");
  return s;
}

Estimate periodOf(const Swings& s) {
  return {2 * s.half_period_s, 2 * s.half_period_error_s};
}

}  // namespace

FreeDecay measureFreeDecay(const std::vector<double>& t_s, const std::vector<double>& theta) {
  const Swings s = enoughSwings(t_s, theta, SwingWindow::Peak, "free decay");
  // log A against t, each point weighted by A^2 (the amplitudes' errors are about equal, so
  // log A's fall as 1/A)
  std::vector<double> t, y, w;
  FreeDecay out;
  for (const Swing& sw : s.swings) {
    t.push_back(sw.t_s);
    y.push_back(std::log(sw.amplitude));
    w.push_back(sw.amplitude * sw.amplitude);
    out.largest_amplitude = std::max(out.largest_amplitude, sw.amplitude);
  }
  const Line l = fitLine(t, y, w);
  out.rate_per_s = {-l.slope, l.slope_error};
  out.period_s = periodOf(s);
  out.swings = static_cast<int>(s.swings.size());
  return out;
}

BoardDecay measureLinearDecay(const std::vector<double>& t_s, const std::vector<double>& x,
                              double gravity_m_s2) {
  const Swings s = enoughSwings(t_s, x, SwingWindow::Crossing, "linear decay");
  std::vector<double> t, y, w;
  for (const Swing& sw : s.swings) t.push_back(sw.t_s), y.push_back(sw.amplitude), w.push_back(1);
  const Line l = fitLine(t, y, w);
  BoardDecay out;
  out.slope_m_per_s = {-l.slope, l.slope_error};
  out.period_s = periodOf(s);
  out.swings = static_cast<int>(s.swings.size());
  // slope = mu-bar T g / pi^2 (s3A); errors of slope and T combined to first order
  const double T = out.period_s.value, k = kPi * kPi / gravity_m_s2;
  const double mu = out.slope_m_per_s.value * k / T;
  const double rel =
      std::hypot(out.slope_m_per_s.std_error / out.slope_m_per_s.value, out.period_s.std_error / T);
  out.mu_bar = {mu, std::abs(mu) * rel};
  return out;
}

SteadyAmplitude measureSteadyAmplitude(const std::vector<double>& t_s,
                                       const std::vector<double>& theta) {
  const Swings s = findSwings(t_s, theta, SwingWindow::Peak);
  const double t_half = 0.5 * (t_s.front() + t_s.back());
  std::vector<double> a;
  for (const Swing& sw : s.swings)
    if (sw.t_s >= t_half) a.push_back(sw.amplitude);
  if (a.size() < 2)
    throw std::invalid_argument("steady amplitude: " + std::to_string(a.size()) +
                                " swings in the last half of the record, at least 2 are needed");
  double mean = 0.0, var = 0.0;
  for (double v : a) mean += v / a.size();
  for (double v : a) var += (v - mean) * (v - mean) / (a.size() - 1);
  SteadyAmplitude out;
  out.amplitude_rad = {mean, std::sqrt(var / a.size())};
  out.swings = static_cast<int>(a.size());
  return out;
}

Estimate dampingFromDecayRate(const Rig& rig, int i, const Estimate& rate_per_s) {
  // the amplitude decays at nu-bar L^2 / (2 I) (yaml/rig_loader.cpp, decay_rate)
  const MetronomeSpec& m = rig.metronomes.at(i);
  const double k = 2.0 * m.inertia_kgm2 / (m.length_m * m.length_m);
  return {k * rate_per_s.value, k * rate_per_s.std_error};
}

Estimate scaledNuFromDecayRate(const Rig& rig, int i, const Estimate& rate_per_s) {
  // eps nu_i = nu-bar_i L_i^2 / (I_i omega0) = 2 beta / omega0
  const ScaledParams sp = computeScaled(rig);
  const double k = 2.0 * sp.time_scale_s / sp.epsilon;
  (void)i;
  return {k * rate_per_s.value, k * rate_per_s.std_error};
}

Impulse impulseFromSteadyAmplitude(const Rig& rig, int i, const Estimate& amplitude_rad,
                                   const Estimate& damping_kg_s) {
  auto scaledJ = [&](double amplitude, double damping) {
    Rig r = rig;
    r.metronomes.at(i).damping_kg_s = damping;
    const ScaledParams sp = computeScaled(r);
    return impulseForAmplitude(sp.nu[i], amplitude / sp.angle_scale, sp.theta_c[i]);
  };
  const double J = scaledJ(amplitude_rad.value, damping_kg_s.value);
  const double ha = kPropagationStep * amplitude_rad.value;
  const double hd = kPropagationStep * damping_kg_s.value;
  const double dJ_da = (scaledJ(amplitude_rad.value + ha, damping_kg_s.value) - J) / ha;
  const double dJ_dd = (scaledJ(amplitude_rad.value, damping_kg_s.value + hd) - J) / hd;
  const double err = std::hypot(dJ_da * amplitude_rad.std_error, dJ_dd * damping_kg_s.std_error);
  // J-bar_i = eps^{3/2} J_i I_i omega0 (models/scaling.h)
  const ScaledParams sp = computeScaled(rig);
  const double k =
      sp.epsilon * sp.angle_scale * rig.metronomes.at(i).inertia_kgm2 / sp.time_scale_s;
  Impulse out;
  out.scaled = {J, err};
  out.impulse_Nms = {k * J, k * err};
  return out;
}

}  // namespace metrosync
