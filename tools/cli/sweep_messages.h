// The messages of a sweep over MPI processes (tools/cli/sweep_mpi.h), as bytes: what a worker
// rank reports to rank 0 (finished points, how many more it wants, points it gives back) and what
// rank 0 answers (grid indices to run, and whether more will ever come). No MPI in here: the
// bytes are what MPI_Send carries. Doubles travel as their 8 bytes, so a point's row written by
// rank 0 is the one the worker computed, bit for bit (NaN and inf included).
#pragma once

#include <string>
#include <vector>

#include "sim/analysis/sweep.h"

namespace metrosync::cli {

// worker -> rank 0
struct SweepReport {
  long want = 0;                   // how many more indices the worker can take now
  bool done = false;               // the worker's last message: it runs nothing more
  std::vector<SweepPoint> points;  // finished since the last report (wall_seconds included)
  std::vector<long> unrun;         // indices given to it that it will not run (a stop request)
};

// rank 0 -> worker
struct SweepWork {
  bool last = false;          // no more indices will come: finish these, report, and end
  std::vector<long> indices;  // grid points to run
};

std::string encodeReport(const SweepReport& r);
// Throws std::runtime_error on bytes that are not a report.
SweepReport decodeReport(const std::string& bytes);
std::string encodeWork(const SweepWork& w);
SweepWork decodeWork(const std::string& bytes);

}  // namespace metrosync::cli
