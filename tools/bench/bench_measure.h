// One measured point of the bench (a scene, a method, a setting): its errors against the
// reference and its timing medians, waiting for a quiet machine before each timed run.
//   in-process engines: a first run recording the envelope (envelope error, regime), repeat - 1
//     more for the envelope timings; then `repeat` runs taking no samples (the final-state
//     timings: the integrator and its events only; their first gives the final-state error and
//     the counts, and its final state is compared with the recording run's)
//   the careful peer: one call of the peer with --repeat (its own CPU and wall medians of the
//     integration, measured inside its process); final state only
#pragma once

#include <string>

#include "tools/bench/bench_report.h"
#include "tools/bench/bench_run.h"

namespace metrosync::bench {

// The options every subcommand of metrosync_bench shares.
struct BenchOptions {
  std::string envelopes;  // directory for every first run's envelope.csv ("" = none)
  int repeat = 5;
  double budget_s = 60;
  double max_load = 1.2;  // 0: do not wait
  double max_wait_s = 3600;
  std::string out = "docs/bench";
  bool quiet = false;
  std::string engine;  // --engine: only this engine's methods ("" = every engine's)
};

// Waits (up to max_wait_s) until the 1-minute load average is below max_load; returns the load
// seen last.
double waitForLoad(const BenchOptions& c);

// One record. `final_timings`: also time the runs without samples (not for the reference and
// its cross-checks, which are run once). `keep` receives the recording run (the reference's).
Record measure(const Scene& scene, const Method& m, const RunResult* ref, const BenchOptions& c,
               double budget_s, int repeat, bool final_timings, RunResult* keep = nullptr);

// The largest |a_k - b_k| (NaN when the sizes differ or either is empty).
double maxAbsDifference(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace metrosync::bench
