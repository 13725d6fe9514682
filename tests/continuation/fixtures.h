// Shared set-ups of the continuation tests: one metronome on a Coulomb platform (a closed-form
// branch in mu) and the paper's f4.4 rig in alpha.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "models/scaling.h"
#include "models/slow_flow.h"
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

// e3.1a for one metronome (J = 2.8, theta_c = 0.9, damping nu) driven by its own amplitude A,
// platform at s = A / mu: dA/dtau = -beta2(s) A - nu A / 2 + (J/pi) sqrt(1 - theta_c^2/A^2).
double amplitudeRate(double A, double s, double nu);

// The fold of the single metronome's ticking states in mu, independently of the continuation:
// along the curve amplitudeRate(A, s) = 0 in the (s, A) plane mu = A / s; its smallest value,
// by bisection for both roots A at each s and golden section over s in [s_lo, s_hi].
double closedFormFoldMu(double nu, double s_lo = 1.0, double s_hi = 4.0);

// The largest residual of the slow flow (max |dz_i/dtau - i Omega z_i|) over all branch points.
double worstResidual(const SlowFlowProblem& prob, const std::vector<Branch>& branches);

// Classical RK4 on the slow flow dz/dtau = f(z) (models/slow_flow.h, modes held) over [0, T] in
// n steps: an integration that shares nothing with the continuation's shooting (Verner 7(6)).
std::vector<std::complex<double>> rk4SlowFlow(const ScaledParams& p, const SlowFlowModes& modes,
                                              std::vector<std::complex<double>> z, double T, int n);

}  // namespace metrosync::continuation::testing
