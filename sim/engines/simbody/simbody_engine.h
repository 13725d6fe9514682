// The full model (e1.1a-c) as a Simbody MultibodySystem: a slider for the platform (absent when
// the platform is fixed), a pin per swinging pendulum, our Coulomb stick-slip element, and the
// escapement as impulsive events. Streams trajectory rows (at rig.sim.sample_s, by interpolation)
// and envelope rows (one per fast period) into `sink`.
#pragma once

#include "models/rig.h"
#include "models/scaling.h"
#include "sim/record/run_report.h"

namespace metrosync {

// Names accepted by simulation.integrator (first = default).
const std::vector<std::string>& simbodyIntegratorNames();

// Runs the rig to rig.sim.t_end_s. Never throws for a failed simulation: the report says
// complete = false and why (non-finite state, step-size underflow, event storm).
RunReport runFullModel(const Rig& rig, RunSink& sink);

}  // namespace metrosync
