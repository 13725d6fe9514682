// Whether a border state of the slow flow (a locked state on A_i = theta_c, where the phase
// equation jumps: sim/analysis/continuation/border_states.h) is stable. The vector field is not
// differentiable there, so no eigenvalue says it; the slow flow itself does: it is integrated
// (sim/engines/slow_flow, which switches the escapement where A_i crosses theta_c) from the state
// moved off it three ways -- every amplitude up, every amplitude down, the phases turned -- and
// the state is stable when every run comes back towards it.
#pragma once

#include <complex>
#include <vector>

#include "models/scaling.h"

namespace metrosync::continuation {

// z: the state (N x 1, 0 for locked metronomes), a fixed point of the rotating frame.
bool slowFlowReturns(const ScaledParams& sp, const std::vector<std::complex<double>>& z);

}  // namespace metrosync::continuation
