// The slow flow: e3.1a-c generalised to N metronomes (paper appendix "ab"; same per-metronome
// derivation, with the platform driven by Z = sum_j A_j e^{i phi_j}).
//
// With s = |Z| / mu, beta = (beta1, beta2)(s) the platform's averaged response
// (contact/averaged_response.h, any friction law) and w_i = Z e^{-i phi_i}:
//   dA_i/dtau        = -beta2 Re w_i - beta1 Im w_i - nu_i A_i / 2
//                      + (J_i/pi) sqrt(1 - theta_c,i^2 / A_i^2) [A_i > theta_c,i]
//   A_i dphi_i/dtau  =  beta1 Re w_i - beta2 Im w_i - (J_i/pi)(theta_c,i / A_i) [A_i > theta_c,i]
//                      - A_i^3 / 16 + alpha_i A_i / 2
// (for N = 2 and psi = phi_1 - phi_2 this is e3.1a-c). It is integrated in the complex amplitudes
// z_i = A_i e^{i phi_i}, free of the 1/A_i of the polar form:
//   dz_i/dtau = (i beta1 - beta2) Z + (-nu_i/2 + i (alpha_i/2 - |z_i|^2/16)) z_i
//               + (J_i/pi) (sqrt(1 - theta_c,i^2/A_i^2) - i theta_c,i/A_i) e^{i phi_i} [A_i >
//               theta_c,i]
// Locked metronomes (ScaledParams::locked) take no part: A = 0 throughout, not in Z. zeta and
// epsilon do not enter (they are O(epsilon) effects); epsilon only sets the output grid.
//
// The right-hand side switches where A_i crosses theta_c,i (escapement on/off: dphi_i/dtau jumps
// by J_i / (pi theta_c,i)) and has kinks where s crosses 1 and s_b = sqrt(1 + pi^2/4) (platform
// regime). The integrator (Dormand-Prince 5(4) with dense output) holds these modes fixed over a
// step, locates the crossings on the dense output and restarts there.
#pragma once

#include <complex>
#include <vector>

#include "contact/averaged_response.h"
#include "models/scaling.h"
#include "sim/run.h"

namespace metrosync {

struct SlowFlowOptions {
  double tau_end = 0.0;       // integrate over [0, tau_end]
  double rtol = 1e-10;        // relative local error target
  double atol = 1e-12;        // absolute local error target
  long max_steps = 20000000;  // accepted + rejected steps; beyond it the run fails
  // event storm (chattering, Zeno): storm_events switches within a tau span of storm_window
  // (times max(1, tau)) fail the run
  int storm_events = 50;
  double storm_window = 1e-6;
};

// Which side of each switching surface the flow is on; the integrator holds these fixed over a
// step. The formulas are continued across the surface (see slowFlowRhs).
struct SlowFlowModes {
  std::vector<bool> engaged;                      // (N x 1) escapement term on: A_i > theta_c,i
  CoulombRegime platform = CoulombRegime::Stuck;  // Coulomb law with mu > 0 only
};

// The modes the paper's indicators give at z: engaged_i = |z_i| > theta_c,i, platform regime of
// s = |Z| / mu.
SlowFlowModes slowFlowModesAt(const ScaledParams& p, const std::vector<std::complex<double>>& z);

// beta1, beta2 for the drive Z = sum of unlocked z_i, with the platform regime of `modes`
// (Coulomb, mu > 0) or the law's constant response (viscous, none, fixed, Coulomb with mu = 0).
AveragedResponse slowFlowBetas(const ScaledParams& p, const SlowFlowModes& modes,
                               const std::vector<std::complex<double>>& z);

// dz_i/dtau, (N x 1); 0 for locked metronomes (whose z is ignored). With explicit modes the
// formulas continue across the switching surfaces: an engaged escapement below theta_c keeps its
// phase term and drops the (clamped) amplitude term; a disengaged one has no term; the platform
// regime's beta formula is used whatever s is (coulombResponseIn).
std::vector<std::complex<double>> slowFlowRhs(const ScaledParams& p, const SlowFlowModes& modes,
                                              const std::vector<std::complex<double>>& z);
// ... with the modes of the state itself (the paper's indicators).
std::vector<std::complex<double>> slowFlowRhs(const ScaledParams& p,
                                              const std::vector<std::complex<double>>& z);

// The polar form (dA_i/dtau, dphi_i/dtau), straight from the equations above with the paper's
// indicators; requires A_i > 0 for unlocked metronomes (locked: 0, 0).
struct SlowFlowPolarRates {
  std::vector<double> dA, dphi;  // (N x 1)
};
SlowFlowPolarRates slowFlowPolarRates(const ScaledParams& p, const std::vector<double>& A,
                                      const std::vector<double>& phi);

// The start: z_i = thetadot0_i + i theta0_i (A_i = sqrt(theta0^2 + thetadot0^2),
// phi_i = atan2(theta0, thetadot0)); 0 for locked metronomes.
std::vector<std::complex<double>> slowFlowStart(const ScaledParams& p);

// Integrates the slow flow from the scaled start and emits envelope rows on the grid
// tau_k = envelopeTau(eps, k) <= opt.tau_end (interpolated from the dense output), with
// psi_j = phi_1 - phi_j unwrapped. final_row is the last row emitted (the state at the end of the
// run when no grid point was reached). A failure (non-finite state, step size underflow, event
// storm, too many steps) ends the run with complete = false and the reason. Throws
// std::invalid_argument on inconsistent parameters (sizes, epsilon <= 0, tau_end < 0, tolerances
// <= 0, mu < 0, guard settings < 1). counts.escapements stays empty: the slow flow has no ticks.
RunReport runSlowFlow(const ScaledParams& p, const SlowFlowOptions& opt, RunSink& sink);

}  // namespace metrosync
