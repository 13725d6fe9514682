// Each key's interval over the likelihood region (docs/fit.md, "What a standard error means").
// Where the cost has neighbouring optima at the noise level a few standard errors apart (a long
// record's rugged cost), which of them a record's best is varies from one noise draw to the next,
// and no single optimum's curvature shows that spread. So every distinct optimum found whose sum
// of squares is within kRegionVariances (Delta chi^2 of kRegionSigmas standard errors) of the
// best's belongs to the region: key j's interval is the union over them of
// x_i -+ sqrt(kRegionVariances - rise_i) se_j (rise_i in variances, se_j the best's curvature
// error: each optimum's own valley to the region's edge, quadratic), and its standard error is the
// larger of se_j and the interval's farther side from the best over kRegionSigmas. With the best
// optimum alone the interval is x -+ kRegionSigmas se_j and the standard error is se_j: no
// inflation where none is due.
#pragma once

#include <optional>
#include <vector>

namespace metrosync {

// The region's edge: 3 standard errors of one key (99.7% of a Gaussian), the same multiple the
// standard errors are read against (docs/bench/fit.md's success: every key within 3).
constexpr double kRegionSigmas = 3.0;
constexpr double kRegionVariances = kRegionSigmas * kRegionSigmas;

// Another optimum: its values and how far its weighted sum of squares lies above the best's, in
// variances (SSR - SSR_best) / sigma^2.
struct RegionOptimum {
  std::vector<double> values;
  double rise = 0.0;
};

struct KeyInterval {
  double lower = 0.0, upper = 0.0;
  double std_error = 0.0;    // max(curvature error, the region's spread / kRegionSigmas)
  bool from_optima = false;  // the region's spread is the larger
};

// Per key (null where `curvature` is): the interval and standard error over the best optimum
// `best` and the `others` within the region (those above it are ignored). `lower_bound` per key:
// an interval does not reach below a key's bound.
std::vector<std::optional<KeyInterval>> likelihoodIntervals(
    const std::vector<double>& best, const std::vector<std::optional<double>>& curvature,
    const std::vector<RegionOptimum>& others, const std::vector<double>& lower_bound);

}  // namespace metrosync
