// What a model says at measured times (docs/fit.md): runs an engine on a rig and reads the
// quantities a data file holds -- theta_i (rad) or x (m) -- at arbitrary times.
//   full model (ModelTrajectory): trajectory rows every `row_dt` and the state after every event;
//     between two of them a cubic Hermite interpolant (angles and rates), or, on an interval that
//     ends at an event (an escapement tick makes the rate jump there), the quadratic through the
//     earlier state, its rate and the later angle
//   slow flow (sampleSlowFlow): the envelope A_i(tau) in rad (A_i sqrt(eps)), interpolated
//     linearly in time
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

// The interval of the model's rows for data sampled at `t_s` (seconds): dt / ceil(dt / (T / 100)),
// dt the data's median spacing, T the small-angle period of metronome 1, so that rows fall on the
// samples of a steady camera.
double modelRowInterval(const std::vector<double>& t_s, const Rig& rig);

// A run of the full model, kept to be read at any time up to its end, with its event records
// (the windows its derivatives jump at: model_jacobian.h).
class ModelTrajectory {
 public:
  // Runs `engine` on `rig` (physical units) to t_end_s, rows every row_dt_s. Throws ModelFailure
  // when the run does not complete, std::invalid_argument for a rig the engine cannot run.
  ModelTrajectory(const Engine& engine, Rig rig, double t_end_s, double row_dt_s);

  // theta_{i+1} (metronome = i >= 0) or x (metronome = -1) at t_s, interpolated
  double at(double t_s, int metronome) const;

  const Rig& rig() const { return rig_; }  // as run (its duration and row interval set)
  const std::vector<EventRecord>& events() const { return events_; }

 private:
  Rig rig_;
  // the knots, in time order: rows in trajectory format (t, x, xdot, theta_1, thetadot_1, ...,
  // platform), `width_` values each, one after another; whether each is the state after an event
  std::vector<double> rows_;
  std::vector<char> after_event_;
  std::size_t width_ = 0;
  std::vector<EventRecord> events_;
  const double* row(std::size_t k) const { return rows_.data() + k * width_; }
};

// The slow flow's amplitude of each requested metronome (metronome >= 0), in rad. Throws
// ModelFailure or std::invalid_argument as above.
std::vector<double> sampleSlowFlow(const Engine& engine, Rig rig,
                                   const std::vector<SampleRequest>& requests);

}  // namespace metrosync
