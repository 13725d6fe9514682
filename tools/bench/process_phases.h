// Where the whole `metrosync run` process's time goes (issue 36): the phases the program says on
// stderr with METROSYNC_PHASES=1 (tools/cli/phase_clock.h) between the start-up before main and
// the exit after its last phase, both measured from outside on the same steady clock, against the
// issue's budget for the whole process, 1.5 x wall_seconds + 3 ms. No I/O: parsing and
// arithmetic, the Markdown and CSV.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace metrosync::bench {

// The budget of the whole process for a run whose summary.json says `wall_seconds` (seconds).
double processBudget(double wall_seconds);

// The marks of one run: "main" at main_at, then each phase's name and length.
struct PhaseMarks {
  double main_at = std::numeric_limits<double>::quiet_NaN();  // steady clock, seconds
  double last_at = std::numeric_limits<double>::quiet_NaN();  // the last phase's end
  std::vector<std::string> names;
  std::vector<double> ms;  // (names.size() x 1)
};

// The lines "metrosync: phase ..." of a run's stderr (other lines ignored). Throws
// std::invalid_argument (the line, what is wrong) for a phase line it cannot read, or when the
// first is not "main".
PhaseMarks parsePhases(const std::string& stderr_text);

// One process measured: from outside (its start and end on the steady clock, its CPU) and from
// within (its marks, summary.json's wall_seconds).
struct ProcessSample {
  double start_s = 0.0, end_s = 0.0, cpu_s = 0.0, wall_seconds = 0.0;
  PhaseMarks marks;
};

// The medians over the runs: "start-up" (to main), each phase in order, "exit" (after the last).
struct ProcessBreakdown {
  int runs = 0;
  std::vector<std::string> phases;
  std::vector<double> ms;                                      // the median of each phase (ms)
  double total_ms = 0.0, cpu_ms = 0.0, wall_seconds_ms = 0.0;  // medians
  double budget_ms = 0.0;                                      // of the median wall_seconds
  // the median over the runs of (total - the sum of the parts): rounding only, as the parts
  // tile the process
  double unaccounted_ms = 0.0;
  bool met() const { return total_ms <= budget_ms; }
};
// Throws std::invalid_argument when no run is given or the runs' phases differ.
ProcessBreakdown processBreakdown(const std::vector<ProcessSample>& runs);

std::string processMarkdown(const ProcessBreakdown& b, const std::string& command);
std::string processCsv(const ProcessBreakdown& b, const std::string& scene, double load_min,
                       double load_max);

}  // namespace metrosync::bench
