// How the validation (sim/analysis/validation/validation.h) compares runs: distances between
// envelope states, the error of a full-model envelope against the slow flow's, orders of
// convergence, and when two final states agree.
#pragma once

#include <vector>

#include "models/scaling.h"
#include "sim/analysis/validation/validation_runs.h"
#include "sim/record/envelope.h"

namespace metrosync {

// Distance between two envelope states in the complex amplitudes of metronome 1's frame,
// w_1 = A_1, w_j = A_j e^{-i psi_j}: max_j |w_j,a - w_j,b|. It weighs a phase error by the
// amplitude, so it stays meaningful where an amplitude is small (a suppressed or dying
// metronome's phase is not).
double envelopeDistance(const EnvelopeRow& a, const EnvelopeRow& b);

struct EnvelopeError {
  double max_distance = 0.0;  // max over rows of envelopeDistance
  double tau_at_max = 0.0;
  double max_dA = 0.0;    // max over rows and metronomes of |dA_i|
  double max_dpsi = 0.0;  // max over rows and j of |wrap(dpsi_j)|, for information
  long rows = 0;          // rows compared
};
// Rows matched on the grid index of epsilon, tau <= tau_max.
EnvelopeError envelopeError(const std::vector<EnvelopeRow>& full,
                            const std::vector<EnvelopeRow>& slow, double epsilon, double tau_max);

// Least-squares slope of log(y) against log(x) (x, y > 0, at least two distinct x).
double fitOrder(const std::vector<double>& x, const std::vector<double>& y);

// Two final states "agree" when their regimes are the same and, for a settled state with some
// metronome alive (in-phase, antiphase, phase-locked, suppression), their envelopeDistance is at
// most this: well above the O(epsilon) differences of the asymptotics at epsilon <= 0.02, well
// below the distance between qualitatively different states (amplitudes are ~2-4).
constexpr double kAgreeDistance = 0.25;
bool finalStatesAgree(const ModelRun& full, const ModelRun& slow, double distance);

// The envelope state with metronomes 1 and 2 exchanged (N = 2): A = (A_2, A_1), psi = -psi.
EnvelopeRow exchangedPair(const EnvelopeRow& row);
// Two metronomes that differ by nothing but their start (the exchange is a symmetry).
bool identicalPair(const ScaledParams& p);

}  // namespace metrosync
