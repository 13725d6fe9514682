#include "sim/analysis/fit/likelihood_region.h"

#include <algorithm>
#include <cmath>

namespace metrosync {

namespace {

// A spread this much beyond the curvature error's (relative) is rounding, not a second valley:
// the standard error stays the curvature's.
constexpr double kSameSpread = 1e-9;

KeyInterval keyInterval(int j, const std::vector<double>& best, double se,
                        const std::vector<RegionOptimum>& others, double lower_bound) {
  KeyInterval k;
  k.lower = best[j] - kRegionSigmas * se;
  k.upper = best[j] + kRegionSigmas * se;
  for (const RegionOptimum& o : others) {
    const double rise = std::max(o.rise, 0.0);
    if (!(rise < kRegionVariances)) continue;
    const double half = std::sqrt(kRegionVariances - rise) * se;
    k.lower = std::min(k.lower, o.values[j] - half);
    k.upper = std::max(k.upper, o.values[j] + half);
  }
  const double farther = std::max(best[j] - k.lower, k.upper - best[j]) / kRegionSigmas;
  k.from_optima = farther > se * (1 + kSameSpread);
  k.std_error = k.from_optima ? farther : se;
  k.lower = std::max(k.lower, lower_bound);
  return k;
}

}  // namespace

std::vector<std::optional<KeyInterval>> likelihoodIntervals(
    const std::vector<double>& best, const std::vector<std::optional<double>>& curvature,
    const std::vector<RegionOptimum>& others, const std::vector<double>& lower_bound) {
  std::vector<std::optional<KeyInterval>> out(best.size());
  for (std::size_t j = 0; j < best.size(); ++j)
    if (curvature[j])
      out[j] = keyInterval(static_cast<int>(j), best, *curvature[j], others, lower_bound[j]);
  return out;
}

}  // namespace metrosync
