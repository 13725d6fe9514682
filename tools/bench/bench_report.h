// What the benchmark writes: one record per (scene, method, setting) with its timings, counts and
// errors; CSV, Markdown tables and gnuplot work-precision / N-scaling plots of them.
#pragma once

#include <limits>
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
  // the runs that record the envelope (the envelope error's timings); for the careful peer, its
  // own medians
  double wall_median_s = 0.0, wall_min_s = 0.0, wall_max_s = 0.0, cpu_median_s = 0.0;
  // the runs that take no samples (the final-state comparison's timings: integration and events
  // only); NaN where not measured
  double wall_final_median_s = std::numeric_limits<double>::quiet_NaN();
  double cpu_final_median_s = std::numeric_limits<double>::quiet_NaN();
  // largest difference between the final states of the two kinds of run (the direct engine
  // promises 0: the same steps either way); NaN where not measured
  double final_sampled_diff = std::numeric_limits<double>::quiet_NaN();
  // `metrosync run` (engine "run"): the medians of summary.json's engine_seconds and of each run's
  // wall_seconds / engine_seconds (its wall_seconds is wall_median_s); NaN elsewhere
  double engine_median_s = std::numeric_limits<double>::quiet_NaN();
  double wall_over_engine = std::numeric_limits<double>::quiet_NaN();
  double load_min = 0.0, load_max = 0.0;  // 1-minute load average before the timed runs
  ErrorVsRef error;  // the envelope error of the recording run, the final-state error of the
                     // final-state run (the same state for the direct engine)
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

// The CPU median of a record's final-state timing (the careful peer's own; elsewhere the runs
// without samples, or the recording runs' where those were not made).
double finalStateCpu(const Record& r);

// The front of one engine (every integrator of it together) or of one engine:integrator label:
// final-state error against finalStateCpu, or envelope error against the recording runs' CPU.
std::vector<WorkPoint> frontOf(const std::vector<Record>& records, const std::string& who,
                               bool final_state);

// Equal-error ratios (CPU) of every pair of engines present, on the final-state and on the
// envelope error, as Markdown and as CSV rows (measure,scene,a,b,error,time_a_s,time_b_s,ratio).
std::string ratiosMarkdown(const std::vector<Record>& records, std::string& csv_rows);

// gnuplot, two panels: final-state error (x) against the final-state runs' CPU median (y), and
// envelope error against the recording runs' CPU median; log-log, one curve per
// engine:integrator.
// Returns false (with a warning on stderr) when gnuplot is missing or fails.
bool plotWorkPrecision(const std::string& png_path, const std::vector<Record>& records,
                       const std::string& title);

// N-scaling: cost per fast period (y) against N (x), log-log, one curve per method.
bool plotNScaling(const std::string& png_path, const std::vector<Record>& records,
                  const std::string& title);
std::string nscaleTable(const std::vector<Record>& records);

}  // namespace metrosync::bench
