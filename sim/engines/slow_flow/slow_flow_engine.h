// The slow flow's engine: integrates models/slow_flow.h (the equations, modes and switching
// functions) from the rig's scaled start and streams envelope rows into a RunSink, like the
// full-model engines. Only the integration loop lives here.
#pragma once

#include "models/slow_flow.h"
#include "sim/events/storm_guard.h"
#include "sim/record/run_report.h"

namespace metrosync {

struct SlowFlowOptions {
  double tau_end = 0.0;       // integrate over [0, tau_end]
  double rtol = 1e-10;        // relative local error target
  double atol = 1e-12;        // absolute local error target
  long max_steps = 20000000;  // accepted + rejected steps; beyond it the run fails
  // The shared storm rule (sim/events/storm_guard.h): more than storm_events switches while tau
  // advances by less than storm_window fast periods (2 pi epsilon in tau) fail the run.
  long storm_events = StormGuard::kMaxEvents;
  double storm_window = StormGuard::kWindowPeriods;
};

// Integrates the slow flow from the scaled start with sim/ode's dopri5 stepper, in a frame that
// turns with the metronomes' mean phase (the flow is invariant under a common rotation; see
// slow_flow_engine.cpp), and emits envelope rows (psi_j = phi_1 - phi_j unwrapped): first the
// start's at tau = 0, then the grid
// tau_k = envelopeTau(eps, k) <= opt.tau_end (interpolated from the dense output), last the state
// where the run ended -- tau_end when it is complete -- which is also final_row (SPEC 3: final is
// the state at the requested end; when tau_end falls exactly on the grid that row appears twice).
// A failure (non-finite state, step size underflow, event storm, too many steps) ends the run with
// complete = false, the reason, and final_row at the tau reached. Throws std::invalid_argument on
// inconsistent parameters (sizes, epsilon <= 0, tau_end < 0, tolerances <= 0, mu < 0, guard
// settings < 1). counts.escapements stays empty: the slow flow has no ticks.
RunReport runSlowFlow(const ScaledParams& p, const SlowFlowOptions& opt, RunSink& sink);

}  // namespace metrosync
