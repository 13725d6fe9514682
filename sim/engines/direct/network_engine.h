// The direct engine for networks of platforms (docs/networks.md): the network's minimal
// coordinates (models/network_equations.h), an embedded Runge-Kutta pair with dense output
// (sim/ode), and the events of every platform through the shared resolver (sim/events): each
// platform has its own EventResolver over a view of the network (its pendulums, the contact under
// it), so ticks, stick-slip and plastic stops follow exactly the rules of one platform
// (docs/events.md). A tick moves only its own platform directly; a platform resting on one that a
// tick moved settles after it (EventResolver::settleAfterSupportImpulse). Witnesses are checked at
// every step end and located on the dense output (a crossing and its return within one step, a
// graze, is not seen: steps are at most kMaxStepPeriods of a period).
#pragma once

#include <string>
#include <vector>

#include "contact/friction_law.h"
#include "models/network.h"
#include "sim/record/run_report.h"

namespace metrosync {

// Runs the network to net.sim.t_end_s. Never throws for a failed simulation (complete = false);
// throws std::invalid_argument for a network it cannot run (an unknown integrator name, no
// swinging pendulum).
RunReport runNetworkDirect(const Network& net, RunSink& sink);

}  // namespace metrosync
