// A sweep from code (docs/library.md): every point of a grid built by the caller, run on threads,
// judged as `metrosync sweep` judges it. The command adds to the same pieces (the grid and the
// scheduler of sim/analysis/sweep.h, the point of sweep_point.h) what a folder needs: files,
// resuming, shards, processes, maps.
#pragma once

#include <functional>
#include <vector>

#include "sim/analysis/sweep.h"
#include "sim/analysis/sweep_point.h"

namespace metrosync {

// Runs every point g < grid.size(): make_point(g) builds it (typically the rig with
// grid.overrides(g) applied; a throw makes the point failed, with the message, of n metronomes
// where n is the first point's), on `jobs` threads; each row goes to on_point as it finishes (one
// at a time, in completion order; may be empty). Returns the rows in grid order. A stop request
// (hooks.stop) leaves the points not yet run out.
std::vector<SweepPoint> runSweep(const SweepGrid& grid,
                                 const std::function<PointInput(long)>& make_point, int jobs,
                                 const std::function<void(const SweepPoint&)>& on_point = {},
                                 const PointHooks& hooks = {});

}  // namespace metrosync
