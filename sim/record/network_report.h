// What a run of a network of platforms (models/network.h, docs/networks.md) returns, and the sink
// it streams its samples into: one form for both engines that run networks (the direct engine,
// sim/engines/direct/network_engine.h, and Simbody, sim/engines/simbody/network_simbody_engine.h),
// so that the network's files (tools/report/network_files.h) do not depend on the engine.
#pragma once

#include <string>
#include <vector>

#include "contact/friction_law.h"
#include "sim/record/run_report.h"

namespace metrosync {

// Receives the state at every sample time (simulation.sample, default period/20) strictly before
// the run's end, then its final state: at exactly the requested end when the run completed.
struct NetworkSink {
  virtual ~NetworkSink() = default;
  // y in the layout of network::Layout (models/network_equations.h: x_p, xdot_p, ..., theta_j,
  // ..., thetadot_j, ..., three ledger quadratures); x_p, xdot_p absolute; modes: each platform's
  // contact mode (Stuck for every non-Coulomb contact).
  virtual void sample(double t, const std::vector<double>& y,
                      const std::vector<PlatformMode>& modes) = 0;
};

struct NetworkRunReport {
  bool complete = true;
  std::string failure;  // why and when it stopped (empty when complete)
  std::string engine = "direct";
  std::string integrator;
  long steps = 0, rhs_evals = 0, events = 0, stick_slip = 0, slip_reversals = 0;
  std::vector<long> ticks;  // per metronome, global numbering (locked ones stay 0)
  EnergyLedger ledger;      // damping_out_J includes the ground and coupling dampers
  double t_end = 0.0;       // the requested end exactly when complete, else where the run stopped
  std::vector<double> final_state;  // in the layout of network::Layout
  double fast_period_s = 0.0;       // 2 pi / omega0 of the network's first swinging pendulum
  // as a single run's (sim/record/run_report.h): the whole run, and its part outside the sink
  double wall_seconds = 0.0, engine_seconds = 0.0;
};

}  // namespace metrosync
