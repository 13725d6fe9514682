// Faults a test injects into sweeps (issue 24: no test hook in production code). `metrosync`
// installs none: every hook is empty and costs one test of an empty std::function. The test-only
// executables metrosync-faults and metrosync-mpi-faults (tests/faults/install_faults.cpp, never
// installed) fill them from their environment before the command line runs:
//   METROSYNC_SWEEP_FAIL_AT=g1,g2,..  those grid points fail as a simulation failure would
//   METROSYNC_SWEEP_STOP_AFTER=K      the process ends like kill -9 after the K-th row written
//   METROSYNC_MPI_KILL_AFTER=R:K      MPI rank R kills itself after running K points
#pragma once

#include <functional>
#include <optional>
#include <string>

namespace metrosync::cli {

struct FaultHooks {
  // grid point g fails with this reason (nullopt: it runs)
  std::function<std::optional<std::string>(long g)> fail_point;
  // after the sweep wrote its k-th row (1-based) in this invocation
  std::function<void(long k)> after_row;
  // after MPI worker rank `rank` ran its k-th point, before reporting it
  std::function<void(int rank, long k)> after_worker_point;
};

// The process's hooks (empty in metrosync).
FaultHooks& faultHooks();

// The reason grid point g is to fail, if a hook says so.
std::optional<std::string> injectedFailure(long g);

}  // namespace metrosync::cli
