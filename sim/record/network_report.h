// The sink a run of a network of platforms (models/network.h, docs/networks.md) streams its samples
// into: one form for both engines that run networks (the direct engine,
// sim/engines/direct/network_engine.h, and Simbody, sim/engines/simbody/network_simbody_engine.h),
// so that the network's files (tools/report/network_files.h) do not depend on the engine. The run
// returns a RunReport (sim/record/run_report.h), the report of every run.
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

}  // namespace metrosync
