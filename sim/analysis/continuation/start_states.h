// Where a continuation starts: the locked state the rig's own start settles to (the slow flow
// integrated by runSlowFlow), or every locked state found by Newton from a grid of seeds.
#pragma once

#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "sim/analysis/continuation/slow_flow_problem.h"

namespace metrosync::continuation {

struct SettledState {
  bool settled = false;
  std::string why;                      // when not settled: what the run did
  std::vector<std::complex<double>> z;  // (N x 1), phi_1 = 0
  double tau = 0.0;                     // end of the run
};

// Integrates the slow flow from the scaled start over [0, tau_end] and checks that the last
// fifth of the run is locked: amplitudes and phase differences constant to kSettleTolerance,
// some metronome still swinging. z is the final state (empty when the run failed or stopped).
SettledState settleOver(const ScaledParams& sp, double tau_end);
// settleOver with tau_end, then 3 and 10 times longer until it settles.
SettledState settleFromStart(const ScaledParams& sp, double tau_end);

// The state from A (N x 1) and psi_j = phi_1 - phi_j (N-1 x 1): z_1 = A_1, z_j = A_j e^{-i psi_j}.
std::vector<std::complex<double>> stateFrom(const std::vector<double>& A,
                                            const std::vector<double>& psi);

// Newton from x0 at p, re-solving with the region of the solution until it lies in the region
// whose formulas it solves; nullopt when that fails.
std::optional<Vec> solveLocked(const SlowFlowProblem& prob, const Vec& x0, double p);

// Every locked state Newton finds at p from a grid of seeds (amplitudes around theta_c and
// A_star, phase differences around the circle; for more than three metronomes the symmetric
// patterns of them only), duplicates merged, the state at rest excepted. The seeds are solved on
// up to `jobs` threads (0: one per hardware thread); the states and their order do not depend on
// it.
std::vector<Vec> allLockedStates(const SlowFlowProblem& prob, double p, int jobs = 1);

}  // namespace metrosync::continuation
