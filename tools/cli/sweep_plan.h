// A sweep's plan (tools/cli/sweep.h): the grid and every point's rig, validated before any
// file is written.
#pragma once

#include <string>
#include <vector>

#include "models/rig.h"
#include "sim/analysis/basin.h"
#include "sim/analysis/continuation/fold_curve.h"
#include "sim/analysis/sweep.h"
#include "tools/cli/sweep_options.h"
#include "tools/report/sweep_files.h"

namespace metrosync::cli {

// The sweep's stages, top to bottom: plan (the grid and every point's rig, validated before any
// file), resume (what the folder already holds), run (points on threads, rows appended as they
// finish), finish (sorted regimes.csv, maps, sweep.json, the console summary).
struct SweepPlan {
  SweepGrid grid;
  SweepShard shard;
  std::string text;  // the rig's YAML
  Rig base;
  int n = 0;
  long mine = 0;  // how many grid points this shard holds (SweepShard::contains says which)
  SweepManifest manifest;
  std::string path, regimes_path;
  std::vector<size_t> map_axes;   // --map
  std::vector<RandomKey> random;  // --random (with --basin-samples)
  int ranks = 1;                  // MPI processes sharing the points (tools/cli/sweep_mpi.h)
};

// The plan of `opt`: the grid, the rig and its corner points checked (RigError, UsageError,
// SweepInputError: nothing written).
SweepPlan planSweep(const SweepOptions& opt);

// The overrides of grid point g's basin sample k: the point's, then the draws of (seed, k).
std::vector<std::string> basinSampleOverrides(const SweepGrid& grid,
                                              const std::vector<RandomKey>& keys, long g, long k);

// --boundaries: the fold and Hopf curves over the map's two ranges.
std::vector<continuation::FoldCurve> mapBoundaries(const SweepOptions& opt, const SweepPlan& plan);

}  // namespace metrosync::cli
