// What a model says at measured times (docs/fit.md): runs an engine on a rig and reads the
// quantities a data file holds -- theta_i (rad) or x (m) -- at arbitrary times.
//   full model: trajectory rows every `row_dt` and the state after every event; between two of
//     them a cubic Hermite interpolant (angles and rates), or, on an interval that ends at an
//     event (an escapement tick makes the rate jump there), the quadratic through the earlier
//     state, its rate and the later angle
//   slow flow: the envelope A_i(tau) in rad (A_i sqrt(eps)), interpolated linearly in time
#pragma once

#include <stdexcept>
#include <vector>

#include "models/rig.h"
#include "sim/engines/engine.h"

namespace metrosync {

// One requested sample: metronome i's angle (its amplitude for the slow flow), or x when
// metronome = -1, at t_s seconds (>= 0).
struct SampleRequest {
  double t_s = 0.0;
  int metronome = -1;
};

// The model's run did not complete (what(): the engine's reason).
struct ModelFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Runs `engine` on `rig` (physical units) to the last requested time and returns the requested
// samples. The full model is sampled every row_dt_s seconds. Throws ModelFailure when the run
// does not complete, std::invalid_argument for a rig the engine cannot run.
std::vector<double> sampleModel(const Engine& engine, Rig rig,
                                const std::vector<SampleRequest>& requests, double row_dt_s);

}  // namespace metrosync
