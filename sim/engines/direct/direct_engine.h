// The full model (e1.1a-c) on a minimal-coordinates engine: the platform's x and one angle per
// swinging pendulum (models/minimal_equations.h), an embedded Runge-Kutta pair with dense output
// (sim/ode/rk_stepper.h), and events located on the dense output to the last few bits.
// Same semantics and same outputs as the Simbody engine (sim/engines/simbody/simbody_engine.h):
// the witnesses, the window resolver, the escapement and Coulomb rules, the storm rule and the
// sample schedule are the shared ones (sim/events/, contact/; docs/events.md); this engine only
// locates the windows, on its dense output, grazing crossings included.
#pragma once

#include <string>
#include <vector>

#include "models/rig.h"
#include "sim/events/storm_guard.h"
#include "sim/record/run_report.h"

namespace metrosync {

// Names accepted by simulation.integrator with this engine.
const std::vector<std::string>& directIntegratorNames();

// The integrator used when simulation.integrator is empty, chosen by measurement (see
// tools/bench/direct_speed.py): verner76 while steps are set by the accuracy (few metronomes:
// fewest operations for a given envelope error), dopri5 once the ticks of many metronomes cut
// every step short (more than 8 swinging: each step then ends at an event and the cheapest step,
// 6 evaluations against verner76's 16, wins; measured 1.9x faster at N = 100 with an envelope
// error of 3e-7 at accuracy 1e-8).
std::string defaultDirectIntegrator(const Rig& rig);

struct DirectOptions {
  // The storm rule's limits (sim/events/storm_guard.h): more than `storm_events` events with time
  // advancing by less than `storm_window` fast periods (2 pi / omega0) ends the run, incomplete.
  long storm_events = StormGuard::kMaxEvents;
  double storm_window = StormGuard::kWindowPeriods;
};

// Runs the rig to rig.sim.t_end_s. Never throws for a failed simulation: the report says
// complete = false and why (non-finite state, step-size underflow, event storm). Throws
// std::invalid_argument for a rig it cannot run (an integrator name that is not its own).
RunReport runDirectModel(const Rig& rig, RunSink& sink, const DirectOptions& options = {});

}  // namespace metrosync
