// `mpirun -np P metrosync-mpi sweep ...` (docs/cluster.md): one sweep over P MPI processes.
// Rank 0 runs the sweep as `metrosync sweep` does (checks, --resume, the lock, regimes.csv rows
// appended as points finish, the sorted file, maps, sweep.json) with the run stage replaced: it
// hands out grid indices on request, in ascending order, a few at a time (dynamic load balancing:
// points differ 100x in cost), runs points itself on its --jobs threads, and writes the rows the
// other ranks send back. Every other rank only runs points, on its own --jobs threads, and writes
// nothing. A point's row depends only on the point, so regimes.csv is the one of `--jobs 1`, bit
// for bit; a rank that dies loses only its points in flight, which --resume runs again.
//
// Protocol (tools/cli/sweep_messages.h): rank 0 sends each worker "start" once its checks passed
// (or "quit" when the command ends before running anything); a started worker sends reports
// (finished points, how many more it wants) and waits for each answer (indices, `last`); its final
// report says `done`. Only the main thread of a process calls MPI (MPI_THREAD_FUNNELED).
#pragma once

#include "tools/cli/basin.h"
#include "tools/cli/sweep.h"

namespace metrosync::cli {

// The `sweep` command on rank 0 of `ranks` processes; returns the exit code. Every worker rank is
// released (quit, or its `done` awaited) before it returns or throws.
int mpiSweepCoordinator(const SweepOptions& opt, int ranks);

// The `sweep` command on a worker rank: waits for rank 0's start, runs what it is given, returns 0.
int mpiSweepWorker(const SweepOptions& opt);

// `mpirun -np P metrosync-mpi basin ...`: the samples scheduled over the ranks as grid points
// are (sample k's draws depend only on the seed and k, so basin.csv is the one of `--jobs 1`).
int mpiBasinCoordinator(const BasinOptions& opt, int ranks);
int mpiBasinWorker(const BasinOptions& opt);

}  // namespace metrosync::cli
