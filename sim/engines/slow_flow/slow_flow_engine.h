// The slow flow's engine: integrates models/slow_flow.h from the rig's scaled start and streams
// envelope rows into a RunSink, like the full-model engines.
#pragma once

#include "models/slow_flow.h"
#include "sim/record/run_report.h"

namespace metrosync {

struct SlowFlowOptions {
  double tau_end = 0.0;       // integrate over [0, tau_end]
  double rtol = 1e-10;        // relative local error target
  double atol = 1e-12;        // absolute local error target
  long max_steps = 20000000;  // accepted + rejected steps; beyond it the run fails
  // event storm (chattering, Zeno): storm_events switches within a tau span of storm_window
  // (times max(1, tau)) fail the run
  int storm_events = 50;
  double storm_window = 1e-6;
};

// Integrates the slow flow from the scaled start and emits envelope rows on the grid
// tau_k = envelopeTau(eps, k) <= opt.tau_end (interpolated from the dense output), with
// psi_j = phi_1 - phi_j unwrapped. final_row is the last row emitted (the state at the end of the
// run when no grid point was reached). A failure (non-finite state, step size underflow, event
// storm, too many steps) ends the run with complete = false and the reason. Throws
// std::invalid_argument on inconsistent parameters (sizes, epsilon <= 0, tau_end < 0, tolerances
// <= 0, mu < 0, guard settings < 1). counts.escapements stays empty: the slow flow has no ticks.
RunReport runSlowFlow(const ScaledParams& p, const SlowFlowOptions& opt, RunSink& sink);

}  // namespace metrosync
