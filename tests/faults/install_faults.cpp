// Linked into the test-only executables metrosync-faults and metrosync-mpi-faults (never into
// metrosync, never installed): fills the fault hooks of tools/cli/fault_hooks.h from the
// environment before main runs, so that end-to-end tests can make grid points fail and end a
// sweep like kill -9 at a chosen row.
#include <signal.h>

#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "tools/cli/fault_hooks.h"

namespace {

using metrosync::cli::faultHooks;

// METROSYNC_SWEEP_FAIL_AT=g1,g2,...
void installFailAt(const char* text) {
  std::vector<long> points;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) points.push_back(std::atol(item.c_str()));
  faultHooks().fail_point = [points](long g) -> std::optional<std::string> {
    for (long p : points)
      if (p == g) return std::string("failure injected by METROSYNC_SWEEP_FAIL_AT, a test hook");
    return std::nullopt;
  };
}

// METROSYNC_SWEEP_STOP_AFTER=K: ended like kill -9 (no sorting, no maps) after the K-th row
void installStopAfter(long k) {
  faultHooks().after_row = [k](long written) {
    if (written == k) std::_Exit(137);
  };
}

// METROSYNC_MPI_KILL_AFTER=R:K: rank R raises SIGKILL once it has run K points
void installKillAfter(const std::string& s) {
  const size_t colon = s.find(':');
  if (colon == std::string::npos) return;
  const int rank = std::atoi(s.substr(0, colon).c_str());
  const long k = std::atol(s.substr(colon + 1).c_str());
  faultHooks().after_worker_point = [rank, k](int r, long ran) {
    if (r == rank && ran == k) ::raise(SIGKILL);
  };
}

const bool installed = [] {
  if (const char* v = std::getenv("METROSYNC_SWEEP_FAIL_AT"); v && *v) installFailAt(v);
  if (const char* v = std::getenv("METROSYNC_SWEEP_STOP_AFTER"); v && *v)
    installStopAfter(std::atol(v));
  if (const char* v = std::getenv("METROSYNC_MPI_KILL_AFTER"); v && *v) installKillAfter(v);
  return true;
}();

}  // namespace
