// The isolated cells of a sweep's regime map read from its folder (sweep.json, regimes.csv):
// sim/analysis/isolated_cells.h on the labels the sweep wrote. `metrosync_isolated_cells DIR`
// (tools/bench/isolated_cells.cpp) prints them; tests/sweep holds the shipped maps to them.
#pragma once

#include <string>
#include <vector>

#include "sim/analysis/isolated_cells.h"
#include "tools/report/sweep_files.h"

namespace metrosync {

struct MapSpeckle {
  SweepManifest manifest;
  std::vector<size_t> axes;         // the map's two axes (positions in manifest.grid.axes())
  std::vector<std::string> labels;  // (grid size x 1) each point's regime, empty: not in the file
  std::vector<IsolatedCell> cells;  // the isolated ones, in index order
};

// The map of the sweep in `dir` on the axes `map_keys` ("KEY1,KEY2"; empty: the first two axes
// of more than one value, as the sweep's own maps). Throws SweepInputError (a folder that is not
// a sweep, a key that is not an axis).
MapSpeckle mapSpeckle(const std::string& dir, const std::string& map_keys = "");

// "N isolated cells of M (L1 in L2: n, ...)" and, with `list`, a line per cell with its values.
std::string speckleText(const MapSpeckle& m, bool list);

}  // namespace metrosync
