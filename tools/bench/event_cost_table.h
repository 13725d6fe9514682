// Cost per step and per event of the direct engine, and where each stands against one evaluation
// of the right-hand side (issue 36, in place of issue 23's N-slope): with 2N ticks a fast period,
// each ending a step, any exact event-driven method pays O(N^2) per period, so the figure to
// watch is what a step and an event cost in RHS evaluations, at N = 2, 8, 32, 128. The run's whole
// cost is divided by its steps, and again by its events (each figure carries the other's work: a
// step's share of the events, an event's share of the steps). No I/O: values and text.
#pragma once

#include <string>
#include <vector>

namespace metrosync::bench {

struct EventCostRow {
  std::string scene, integrator;
  int n = 0;  // metronomes
  double accuracy = 0.0;
  long steps = 0, rhs_evals = 0, events = 0;
  double cpu_s = 0.0;  // the run without samples (CPU median)
  double rhs_s = 0.0;  // one RHS evaluation alone (CPU median over batches)
  int runs = 0;
  std::string failure;  // "" when measured

  double evalsPerStep() const { return static_cast<double>(rhs_evals) / steps; }
  double evalsPerEvent() const { return static_cast<double>(rhs_evals) / events; }
  double secondsPerStep() const { return cpu_s / steps; }
  double secondsPerEvent() const { return cpu_s / events; }
  // the same in units of one RHS evaluation's time
  double stepInRhs() const { return secondsPerStep() / rhs_s; }
  double eventInRhs() const { return secondsPerEvent() / rhs_s; }
  // the share of the run's time spent evaluating the right-hand side
  double rhsShare() const { return rhs_evals * rhs_s / cpu_s; }
};

std::string eventCostCsv(const std::vector<EventCostRow>& rows, double load_min, double load_max);
std::string eventCostMarkdown(const std::vector<EventCostRow>& rows, const std::string& command);

}  // namespace metrosync::bench
