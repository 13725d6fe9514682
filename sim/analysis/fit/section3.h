// The paper's section-3 measurements as closed forms on measured swings (docs/fit.md), each with
// its standard error from the least-squares fit it comes from:
//   free decay (s3, "Measuring the other system parameters"): one pendulum below theta_c on a
//     still table, theta ~ A e^{-beta t} cos(w t): beta from the slope of log(amplitude) against
//     time; then nu-bar = 2 beta I / L^2 and the scaled nu = 2 beta / (eps omega0)
//   linear decay (s3A, eq3.1-eq3.2): the board on springs with the metronomes locked, its swing
//     falling by 4 mu-bar M g / k a period: slope = mu-bar T g / pi^2, so mu-bar = slope pi^2 / (T
//     g)
//   steady amplitude (eq. J_estimate): A_star of one ticking metronome on a still table gives
//     J = (pi / 2) nu A_star / sqrt(1 - theta_c^2 / A_star^2) (scaled), J-bar = eps^{3/2} J I
//     omega0
#pragma once

#include <string>
#include <vector>

#include "models/rig.h"

namespace metrosync {

struct Estimate {
  double value = 0.0;
  double std_error = 0.0;  // one standard deviation
};

// Free decay: beta (1/s) from the swings of theta (rad) below theta_c. Throws
// std::invalid_argument when the record holds fewer than 3 swings.
struct FreeDecay {
  Estimate rate_per_s;             // beta, the rig key pendulum.decay_rate
  Estimate period_s;               // the measured period
  int swings = 0;                  // used in the fit
  double largest_amplitude = 0.0;  // rad, to check against theta_c
};
FreeDecay measureFreeDecay(const std::vector<double>& t_s, const std::vector<double>& theta);

// Linear decay of the board's swing (x in m): the slope of its amplitude against time, the
// period, and mu-bar. Throws std::invalid_argument with fewer than 3 swings.
struct BoardDecay {
  Estimate slope_m_per_s;  // how fast the amplitude falls
  Estimate period_s;
  Estimate mu_bar;  // the rig key platform.friction.mu
  int swings = 0;
};
BoardDecay measureLinearDecay(const std::vector<double>& t_s, const std::vector<double>& x,
                              double gravity_m_s2);

// Steady amplitude (rad): the mean swing over the last half of the record (standard error of the
// mean). Throws std::invalid_argument with fewer than 2 swings there.
struct SteadyAmplitude {
  Estimate amplitude_rad;  // the rig key escapement.steady_amplitude
  int swings = 0;
};
SteadyAmplitude measureSteadyAmplitude(const std::vector<double>& t_s,
                                       const std::vector<double>& theta);

// The rig's units for a measured decay rate of metronome i: nu-bar (kg/s) and the scaled nu.
Estimate dampingFromDecayRate(const Rig& rig, int i, const Estimate& rate_per_s);
Estimate scaledNuFromDecayRate(const Rig& rig, int i, const Estimate& rate_per_s);

// eq. J_estimate for metronome i of `rig` (its scaled nu from `damping_kg_s`, its theta_c) at the
// steady amplitude `amplitude_rad`; errors propagated to first order from both. Scaled J and
// J-bar (N m s). Throws std::invalid_argument when the amplitude is below sqrt(2) theta_c.
struct Impulse {
  Estimate scaled;
  Estimate impulse_Nms;  // the rig key escapement.impulse
};
Impulse impulseFromSteadyAmplitude(const Rig& rig, int i, const Estimate& amplitude_rad,
                                   const Estimate& damping_kg_s);

}  // namespace metrosync
