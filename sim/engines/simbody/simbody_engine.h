// The Simbody engine's one entry: the full model (e1.1a-c) of a network of platforms
// (models/network.h, docs/networks.md) -- a single-platform rig is the network of one,
// networkOfOne(rig) -- built by the one builder (models/simbody/platform_system.h), run by the one
// run loop (platform_run.h) with the escapement as impulsive events and the event semantics of the
// direct engine through the shared resolver, recorded by one recorder into the one sink
// (sim/record/run_report.h RunSink): a single rig's rows (trajectory at simulation.sample by
// interpolation, envelope on the shared schedule and on both sides of every event, event rows and
// the event record) and, when the sink wantsStates(), the network's state at every sample.
#pragma once

#include <string>
#include <vector>

#include "models/network.h"
#include "sim/record/run_report.h"

namespace metrosync {

// Names accepted by simulation.integrator (first = default).
const std::vector<std::string>& simbodyIntegratorNames();

// Runs the network to net.sim.t_end_s with net.sim.integrator (empty: the default, rk-merson) at
// net.sim.accuracy. A single rig (net.isSingleRig()) reports as it always has: its rows and
// failure in the rig's units, its events the windows; a network's report adds its final state
// (network::Layout), t_end and fast period, its events the windows, forced stops and event rows.
// Never throws for a failed simulation: the report says complete = false and why (non-finite
// state, step-size underflow, event storm). Throws std::invalid_argument for a network it cannot
// run (an unknown integrator, a network without a swinging pendulum).
RunReport runSimbody(const Network& net, RunSink& sink);

}  // namespace metrosync
