// The full model (e1.1a-c) on Simbody for a single-platform rig: the rig as a network of one
// (models/simbody/platform_system.h: a slider for the platform, absent when it is fixed, a pin per
// swinging pendulum, the Coulomb contact), run by the one run loop (platform_run.h) with the
// escapement as impulsive events. Streams trajectory rows (at rig.sim.sample_s, by
// interpolation), envelope rows (one per fast period) and event rows into `sink`.
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
