// What one fit costs (issue 36): the fit bench (`metrosync_fit_bench`,
// tools/bench/fit_recovery.cpp: five keys from starts 50% off, Simbody records) run on fewer or all
// of its records, one fit at a time (--jobs 1: each fit has the machine), each fit's wall and CPU
// time; then one `metrosync run` of each record's own rig (`--quiet --no-plot`, K runs after one
// that warms the page cache), and each fit's wall time against that run's wall_seconds (median).
// Targets: the median fit <= 1 s of wall time on 2 cores, and <= 100 times one run.
#pragma once

#include <string>
#include <vector>

#include "tools/bench/bench_measure.h"
#include "tools/bench/speed_targets.h"

namespace metrosync::bench {

struct FitCostOptions {
  std::string fit_bench = "build/metrosync_fit_bench";
  std::string metrosync = "build/metrosync";
  int records = 50;
  double duration_s = 30;  // seconds per record (docs/bench/fit.md's)
  unsigned seed = 1;
  int run_repeat = 5;
};

struct FitRecordCost {
  int record = 0;
  double wall_s = 0.0, cpu_s = 0.0;  // the fit's
  long model_runs = 0;
  bool recovered = false;
  double run_s = 0.0;  // one `metrosync run` of its rig: the median wall_seconds
  std::string error;
};

struct FitCost {
  std::vector<FitRecordCost> records;
  std::string command;  // the fit bench's
  std::string failure;  // "" when measured
  double load_min = 0.0, load_max = 0.0;
};

FitCost measureFitCost(const FitCostOptions& o, const BenchOptions& c);

std::string fitCostCsv(const FitCost& f);
std::string fitCostMarkdown(const FitCost& f, const FitCostOptions& o);

}  // namespace metrosync::bench
