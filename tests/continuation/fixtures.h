// Shared set-ups of the continuation tests: one metronome on a Coulomb platform (a closed-form
// branch in mu) and the paper's f4.4 rig in alpha.
#pragma once

#include <string>

#include "models/scaling.h"
#include "sim/analysis/continuation/arclength.h"
#include "sim/analysis/continuation/slow_flow_problem.h"
#include "sim/analysis/continuation/start_states.h"

namespace metrosync::continuation::testing {

// One metronome (nu = 0.7, J = 2.8, theta_c = 0.9, the paper's values) on a Coulomb platform
// with scaled friction mu.
ScaledParams singleMetronome(double mu);

// The paper's f4.4 rig (yaml/rigs/paper/f4.4-alpha4.yaml) with metronomes.1.alpha = alpha.
ScaledParams f44(double alpha);

// The ticking state of the single metronome at mu on the upper (stable) root of the amplitude
// equation, as the problem's x, by bisection on A (independent of the continuation's Newton).
Vec singleTicking(const SlowFlowProblem& prob, double mu);

// The largest residual of the slow flow (max |dz_i/dtau - i Omega z_i|) over all branch points.
double worstResidual(const SlowFlowProblem& prob, const std::vector<Branch>& branches);

}  // namespace metrosync::continuation::testing
