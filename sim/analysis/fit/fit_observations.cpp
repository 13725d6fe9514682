#include "sim/analysis/fit/fit_observations.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/analysis/fit/noise_level.h"
#include "sim/analysis/fit/swings.h"

namespace metrosync {

namespace {

// The noise of each column: --noise for the angles (for x when only x is measured), the data's
// estimate for the rest.
void columnNoise(const MeasuredData& data, const std::vector<double>& theta_c,
                 std::optional<double> given, FitData& d) {
  const std::vector<bool> ticks = escapementTicks(data, theta_c);
  bool any_angle = false;
  for (int m : d.metronome) any_angle = any_angle || m >= 0;
  bool estimated = false, reliable = true;
  for (std::size_t q = 0; q < d.quantity_names.size(); ++q) {
    const bool angle = d.metronome[q] >= 0;
    if (given && (angle || !any_angle)) {
      d.noise.push_back(*given);
      continue;
    }
    const NoiseEstimate e = estimateNoise(data, *data.find(d.quantity_names[q]), ticks);
    d.noise.push_back(e.sigma);
    estimated = true;
    reliable = reliable && e.reliable;
  }
  d.noise_reliable = reliable;
  for (double s : d.noise) d.noise_reliable = d.noise_reliable && s > 0;
  d.noise_from = !estimated ? "--noise" : !d.noise_reliable ? "data (upper bound)" : "data";
  if (given && estimated) d.noise_from = "--noise and data";
  bool any = false;
  for (double s : d.noise) any = any || s > 0;
  if (!any) d.noise_from = "unknown";
}

}  // namespace

FitData fitData(const MeasuredData& data, bool slow, const std::vector<double>& theta_c,
                std::optional<double> noise) {
  FitData d;
  std::vector<double> amplitude_error;  // slow: per observation, per unit of noise
  for (const DataColumn& c : data.columns) {
    if (slow && c.metronome < 0) {
      d.warnings.push_back("--model slow: column " + c.name + " is not used");
      continue;
    }
    const int q = static_cast<int>(d.quantity_names.size());
    const int group = c.metronome < 0 ? 1 : 0;
    d.quantity_names.push_back(c.name);
    d.metronome.push_back(c.metronome);
    if (slow) {
      for (const Swing& w : findSwings(data.t_s, c.values, SwingWindow::Peak).swings) {
        d.observations.push_back({w.t_s, q, group, w.amplitude});
        amplitude_error.push_back(w.error_per_noise);
      }
    } else {
      for (std::size_t i = 0; i < data.t_s.size(); ++i)
        if (data.t_s[i] >= 0 && !std::isnan(c.values[i]))
          d.observations.push_back({data.t_s[i], q, group, c.values[i]});
    }
  }
  if (d.observations.empty()) throw std::invalid_argument("no sample to fit");
  // only lengths: they are the first group
  bool any_angle = false;
  for (int m : d.metronome) any_angle = any_angle || m >= 0;
  if (!any_angle)
    for (Observation& o : d.observations) o.group = 0;
  columnNoise(data, theta_c, noise, d);
  if (slow) {  // an amplitude's noise: the samples' through its window's fit (RMS per column)
    std::vector<double> sum(d.noise.size(), 0.0), count(d.noise.size(), 0.0);
    for (std::size_t i = 0; i < d.observations.size(); ++i) {
      const int q = d.observations[i].quantity;
      sum[q] += std::pow(d.noise[q] * amplitude_error[i], 2);
      count[q] += 1;
    }
    for (std::size_t q = 0; q < d.noise.size(); ++q)
      d.noise[q] = count[q] > 0 ? std::sqrt(sum[q] / count[q]) : 0.0;
  }
  std::stable_sort(d.observations.begin(), d.observations.end(),
                   [](const Observation& a, const Observation& b) { return a.t_s < b.t_s; });
  return d;
}

}  // namespace metrosync
