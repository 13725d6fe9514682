// The Simbody engine for networks of platforms (docs/networks.md): the network as one Simbody
// MultibodySystem (models/simbody/network_system.h), Simbody's integrators, thin witnesses, and
// the event semantics of the direct network engine (sim/engines/direct/network_engine.h) through
// the shared resolver: one EventResolver per platform over a view of the Simbody state (its
// pendulums, the contact under it), every due tick of a window applied as one impulse through
// Simbody's full mass matrix with every contact free, then each platform's Coulomb rule, then the
// platforms whose support an impulse moved. Streams the same samples into the same sink.
#pragma once

#include "models/network.h"
#include "sim/record/network_report.h"

namespace metrosync {

// Runs the network to net.sim.t_end_s with net.sim.integrator (a Simbody integrator; empty: the
// default, rk-merson). Never throws for a failed simulation (complete = false); throws
// std::invalid_argument for a network it cannot run (an unknown integrator, no swinging pendulum).
NetworkRunReport runNetworkSimbody(const Network& net, NetworkSink& sink);

}  // namespace metrosync
