// Identical metronomes exchanged. The slow flow is equivariant under every exchange sigma of
// metronomes with equal parameters (nu, J, theta_c, alpha, locked): when z is a locked state, so
// is z'_i = z_sigma(i), and the branch through z' is the branch through z with its metronomes
// exchanged, point for point, with the same eigenvalues and bifurcations. `continue --all` on 32
// identical metronomes finds one state for each metronome suppressed or set against the rest:
// each such copy's branches are mapped from the first one's instead of followed again.
#pragma once

#include <complex>
#include <optional>
#include <vector>

#include "sim/analysis/continuation/branch.h"
#include "sim/analysis/continuation/slow_flow_problem.h"

namespace metrosync::continuation {

// For each metronome, the first metronome (0-based) it may be exchanged with: equal slow-flow
// parameters at the range's ends and at kSamples values between them (a key that sets one
// metronome's parameter, e.g. metronomes.1.alpha, makes it differ at one end at least).
std::vector<int> exchangeClasses(const ParamsAt& params, double from, double to);

// An exchange sigma (z'_i = e^{ic} z_sigma(i) for one rotation c, within `tolerance` in every
// z_i) that maps z onto `copy`, exchanging metronomes of one class only; nullopt when there is
// none (or the state is at rest).
std::optional<std::vector<int>> exchangeOf(const std::vector<std::complex<double>>& copy,
                                           const std::vector<std::complex<double>>& z,
                                           const std::vector<int>& classes, double tolerance);

// The reference metronome of a copy problem: the one exchanged onto the original's reference.
int exchangedReference(const std::vector<int>& sigma, int reference);

// The branches of `from` with the metronomes exchanged by sigma, in the coordinates of `to` (a
// problem whose reference is exchangedReference(sigma, from.reference())): each point's state,
// tangent, region and special points mapped; eigenvalues, stability and ends as they are.
std::vector<Branch> exchangedBranches(const SlowFlowProblem& from, const SlowFlowProblem& to,
                                      const std::vector<int>& sigma,
                                      const std::vector<Branch>& branches);

}  // namespace metrosync::continuation
