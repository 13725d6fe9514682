// The Simbody engine's entry for a network of platforms (docs/networks.md): the network's system
// from the one builder (models/simbody/platform_system.h), run by the one run loop
// (sim/engines/simbody/platform_run.h) that also runs single rigs, with the event semantics of
// the direct network engine (sim/engines/direct/network_engine.h) through the shared resolver.
// Streams its samples (network::Layout) into the sink.
#pragma once

#include "models/network.h"
#include "sim/record/network_report.h"

namespace metrosync {

// Runs the network to net.sim.t_end_s with net.sim.integrator (a Simbody integrator; empty: the
// default, rk-merson). Never throws for a failed simulation (complete = false); throws
// std::invalid_argument for a network it cannot run (an unknown integrator, no swinging pendulum).
RunReport runNetworkSimbody(const Network& net, NetworkSink& sink);

}  // namespace metrosync
