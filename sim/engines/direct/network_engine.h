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

// Receives the state at every sample time (simulation.sample, default period/20) and at the end.
struct NetworkSink {
  virtual ~NetworkSink() = default;
  // y in the layout of network::Layout (x_p, xdot_p, ..., theta_j, ..., thetadot_j, ...);
  // modes: each platform's contact mode (Stuck for every non-Coulomb contact).
  virtual void sample(double t, const std::vector<double>& y,
                      const std::vector<PlatformMode>& modes) = 0;
};

struct NetworkRunReport {
  bool complete = true;
  std::string failure;  // why and when it stopped (empty when complete)
  std::string integrator;
  long steps = 0, rhs_evals = 0, events = 0, stick_slip = 0, slip_reversals = 0;
  std::vector<long> ticks;  // per metronome, global numbering (locked ones stay 0)
  EnergyLedger ledger;      // damping_out_J includes the ground and coupling dampers
  double t_end = 0.0;
  std::vector<double> final_state;
  double fast_period_s = 0.0;  // 2 pi / omega0 of the network's first swinging pendulum
};

// Runs the network to net.sim.t_end_s. Never throws for a failed simulation (complete = false);
// throws std::invalid_argument for a network it cannot run (an unknown integrator name, no
// swinging pendulum).
NetworkRunReport runNetworkDirect(const Network& net, NetworkSink& sink);

}  // namespace metrosync
