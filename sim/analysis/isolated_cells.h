// Isolated cells of a regime map (issue 37): a cell of a sweep's two-dimensional map whose four
// neighbours on the map's axes all share one label other than its own -- a speck of one label
// inside another's region. A map whose labels are those of the attractors has few: where the
// state changes with the parameters, regions meet along curves, and a cell alone inside another
// region is either a feature narrower than the grid (a tongue's tip, a basin boundary's own
// state) or a label that depends on something else than the attractor (when the run's window
// happened to see a transient). A cell on the map's edge (fewer than four neighbours) or with a
// neighbour that has no label is not counted. A grid of more than two axes is counted in every
// slice of the other axes.
#pragma once

#include <string>
#include <vector>

#include "sim/analysis/sweep.h"

namespace metrosync {

struct IsolatedCell {
  long index = 0;          // the grid index (regimes.csv's `index`)
  std::string label;       // its regime
  std::string neighbours;  // the one regime of its four neighbours
};

// The isolated cells of `labels` (one per grid index; an empty text: no point there) on the map
// whose axes are `map_axes` (two positions in grid.axes(), across then up: mapAxes()), in index
// order. Fewer than two axes: none.
std::vector<IsolatedCell> isolatedCells(const SweepGrid& grid, const std::vector<size_t>& map_axes,
                                        const std::vector<std::string>& labels);

}  // namespace metrosync
