// The full model (e1.1a-c) on a minimal-coordinates engine: the platform's x and one angle per
// swinging pendulum (models/network_equations.h), an embedded Runge-Kutta pair with dense output
// (sim/ode/rk_stepper.h), and events located on the dense output to the last few bits.
// Same semantics and same outputs as the Simbody engine (sim/engines/simbody/simbody_engine.h):
// the witnesses, the window resolver, the escapement and Coulomb rules, the storm rule and the
// sample schedule are the shared ones (sim/events/, contact/; docs/events.md); this engine only
// locates the windows, on its dense output, grazing crossings included.
#pragma once

#include <string>
#include <vector>

#include "models/network.h"
#include "models/rig.h"
#include "sim/engines/direct/direct_integrators.h"
#include "sim/engines/direct/direct_options.h"
#include "sim/record/run_report.h"

namespace metrosync {

// Runs the rig or network to net.sim.t_end_s on the one model (direct_model.h): a single board
// (Network::isSingleRig) writes a rig's rows, envelope and events into the sink (and its states
// when the sink wants them), a network its states (sink.stateSample, the last at t_end exactly).
// Never throws for a failed simulation: the report says complete = false and why (non-finite
// state, step-size underflow, event storm). Throws std::invalid_argument for a rig it cannot run
// (an integrator name that is not its own).
RunReport runDirect(const Network& net, RunSink& sink, const DirectOptions& options = {});

// runDirect on the rig's network of one (models/network.h, networkOfOne).
RunReport runDirectModel(const Rig& rig, RunSink& sink, const DirectOptions& options = {});

}  // namespace metrosync
