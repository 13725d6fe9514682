// What the benchmark writes: one record per (scene, method, setting) with its timings, counts and
// errors; CSV, Markdown tables and gnuplot work-precision / N-scaling plots of them.
#pragma once

#include <string>
#include <vector>

#include "tools/bench/bench_metrics.h"
#include "tools/bench/bench_run.h"

namespace metrosync::bench {

struct Record {
  std::string scene;
  int n_metronomes = 0;
  double periods = 0.0;  // fast periods in the run
  Method method;
  // ok | reference | cross-check | over budget | skipped (predicted over budget) | failed
  std::string status;
  std::string note;  // why it failed or was skipped
  int runs = 0;      // timed runs behind the medians
  double wall_median_s = 0.0, wall_min_s = 0.0, wall_max_s = 0.0, cpu_median_s = 0.0;
  double load_min = 0.0, load_max = 0.0;  // 1-minute load average before the timed runs
  ErrorVsRef error;
  long steps = 0, rhs_evals = 0, events = 0, ticks = 0, stick_slip = 0;
  std::string regime;
  bool timed() const {
    return runs > 0 && (status == "ok" || status == "reference" || status == "cross-check");
  }
};

std::string csvHeader();
std::string csvRow(const Record& r);
std::string recordsCsv(const std::vector<Record>& records);

// The work-precision table of one scene (Markdown), the reference and its cross-check first.
std::string precisionTable(const std::vector<Record>& records);

// The front of one engine (every integrator of it together) or of one engine:integrator label.
std::vector<WorkPoint> frontOf(const std::vector<Record>& records, const std::string& who);

// Equal-error ratios of every pair of engines present, as Markdown and as CSV rows
// (scene,a,b,error,time_a_s,time_b_s,ratio).
std::string ratiosMarkdown(const std::vector<Record>& records, std::string& csv_rows);

// gnuplot: error (x) against median wall time (y), log-log, one curve per engine:integrator.
// Returns false (with a warning on stderr) when gnuplot is missing or fails.
bool plotWorkPrecision(const std::string& png_path, const std::vector<Record>& records,
                       const std::string& title);

// N-scaling: cost per fast period (y) against N (x), log-log, one curve per method.
bool plotNScaling(const std::string& png_path, const std::vector<Record>& records,
                  const std::string& title);
std::string nscaleTable(const std::vector<Record>& records);

}  // namespace metrosync::bench
