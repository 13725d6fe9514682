// `metrosync sweep` and `metrosync merge` (SPEC section 2): regime maps over one or two rig keys,
// run in parallel, resumable, in shards that merge joins. The grid, the points and the scheduling
// are sim/analysis/sweep.h, the files tools/report/sweep_files.h, the maps
// tools/report/sweep_maps.h; this is the command line and how one point runs.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sim/analysis/sweep.h"
#include "tools/cli/sweep_options.h"
#include "tools/cli/sweep_point_run.h"

namespace metrosync::cli {

// Each returns the exit code (SPEC 5); a bad rig or command line throws RigError or UsageError
// (exit 2) before anything is written.
int sweepCommand(const SweepOptions& opt);
int mergeCommand(const SweepOptions& opt);

// ---- for other ways of running the points (MPI: tools/cli/sweep_mpi.h) -------------------------

// How one grid point runs: its row, or nullopt when a stop request interrupted it.
using SweepPointRunner = std::function<std::optional<SweepPoint>(long)>;
using SweepPointSink = std::function<void(const SweepPoint&)>;
// The run stage's scheduler, runSweepPoints's contract (sim/analysis/sweep.h): run every g <
// size with wanted(g), hand each result to `finished` (never two at once), stop starting points
// once stop() is true, rethrow the first exception; return how many threads of this process ran
// points (fewer than `jobs` when there are fewer points, or the system refused more threads).
using SweepScheduler = std::function<int(
    long size, const std::function<bool(long)>& wanted, int jobs, const SweepPointRunner& run,
    const SweepPointSink& finished, const std::function<bool()>& stop)>;

// The sweep with its points run by `schedule` (on `ranks` processes, for the summary and
// sweep.json); everything else (checks, --resume, files, maps) as sweepCommand(opt).
int sweepCommand(const SweepOptions& opt, const SweepScheduler& schedule, int ranks);

// A process that only runs points for another one: checks `opt` as the sweep does (RigError or
// UsageError, nothing written) and returns how grid point g runs.
SweepPointRunner sweepPointRunner(const SweepOptions& opt);

}  // namespace metrosync::cli
