// The median of a sample, as the fits use it (sim/analysis/fit: the swings' windows, the noise
// level's second differences): its middle element once sorted, the upper of the two middle ones
// for an even count; 0 for an empty sample.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace metrosync {

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  return v[mid];
}

}  // namespace metrosync
