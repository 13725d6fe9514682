#include "sim/analysis/isolated_cells.h"

#include <algorithm>

namespace metrosync {

namespace {

// The grid index of the neighbour of `index` one step along `axis` (step = +-1), -1 off the grid.
long neighbour(const SweepGrid& grid, long index, size_t axis, int step) {
  const std::vector<long> at = grid.coordinates(index);
  const long to = at[axis] + step;
  if (to < 0 || to >= grid.axes()[axis].count) return -1;
  long stride = 1;
  for (size_t k = axis + 1; k < grid.axes().size(); ++k) stride *= grid.axes()[k].count;
  return index + step * stride;
}

}  // namespace

std::vector<IsolatedCell> isolatedCells(const SweepGrid& grid, const std::vector<size_t>& map_axes,
                                        const std::vector<std::string>& labels) {
  std::vector<IsolatedCell> cells;
  if (map_axes.size() < 2) return cells;
  const long n = std::min<long>(grid.size(), static_cast<long>(labels.size()));
  for (long g = 0; g < n; ++g) {
    if (labels[g].empty()) continue;
    std::string other;
    int same = 0;
    for (size_t axis : {map_axes[0], map_axes[1]})
      for (int step : {-1, 1}) {
        const long k = neighbour(grid, g, axis, step);
        if (k < 0 || k >= n || labels[k].empty()) continue;  // not four neighbours
        if (other.empty()) other = labels[k];
        same += labels[k] == other;
      }
    if (same == 4 && other != labels[g]) cells.push_back({g, labels[g], other});
  }
  return cells;
}

}  // namespace metrosync
