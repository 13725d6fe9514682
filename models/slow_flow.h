// The slow flow (e3.1a-c generalised to N metronomes; to be implemented).
#pragma once

#include "models/scaling.h"
#include "sim/run.h"

namespace metrosync {

struct SlowFlowOptions {
  double tau_end = 0.0;   // integrate over [0, tau_end]
  double rtol = 1e-10;    // relative local error target
  double atol = 1e-12;    // absolute local error target
};

// Integrates the slow flow from the scaled start (A_i = sqrt(theta0^2 + thetadot0^2),
// phi_i = atan2(theta0, thetadot0)) and emits envelope rows on the grid envelopeTau(eps, k).
RunReport runSlowFlow(const ScaledParams& p, const SlowFlowOptions& opt, RunSink& sink);

}  // namespace metrosync
