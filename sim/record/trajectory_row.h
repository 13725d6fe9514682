// A single rig's trajectory row (docs/outputs.md, trajectory.csv and events.csv), made by one
// function for both engines: t, x, xdot, then theta_i, thetadot_i of every metronome in the rig's
// order (0, 0 for a locked one), then the platform column (-1, 0, 1: its slip direction, 0 stuck).
// A physical rig's row is in SI units, a scaled rig's in its scaled variables (x / x_scale,
// theta / angle_scale, t omega0). The engines hand it their state's numbers; the row is the same
// arithmetic whichever engine made the state.
#pragma once

#include <utility>
#include <vector>

#include "models/rig.h"
#include "models/scaling.h"

namespace metrosync {

// Each metronome's swinging pendulum when the pendulums are the swinging metronomes in the rig's
// order (-1 for a locked one): TrajectoryRow's `pendulum` of a state laid out so.
inline std::vector<int> swingingPendulums(const Rig& rig) {
  std::vector<int> p;
  int j = 0;
  for (const MetronomeSpec& m : rig.metronomes) p.push_back(m.locked ? -1 : j++);
  return p;
}

class TrajectoryRow {
 public:
  // `pendulum[i]`: metronome i's swinging pendulum in the engine's state (its index there), or -1
  // for a locked one.
  TrajectoryRow(const Rig& rig, const ScaledParams& sp, std::vector<int> pendulum)
      : pendulum_(std::move(pendulum)) {
    if (rig.units != Units::Scaled) return;
    xs_ = 1.0 / sp.x_scale_m;
    as_ = 1.0 / sp.angle_scale;
    ts_ = 1.0 / sp.time_scale_s;
  }
  std::size_t size() const { return 2 * pendulum_.size() + 4; }

  // Fills `row` (resized to size()) from the state at t (seconds): x, v the board's position
  // (m) and velocity (m/s), theta(j) and omega(j) swinging pendulum j's angle (rad) and rate
  // (rad/s), `column` the platform's.
  template <class Theta, class Omega>
  void fill(std::vector<double>& row, double t, double x, double v, const Theta& theta,
            const Omega& omega, int column) const {
    row.resize(size());  // written in place: no growth checks
    double* out = row.data();
    *out++ = t * ts_;
    *out++ = x * xs_;
    *out++ = v * xs_ / ts_;
    for (int j : pendulum_) {
      if (j < 0) {
        *out++ = 0.0;
        *out++ = 0.0;
        continue;
      }
      *out++ = theta(j) * as_;
      *out++ = omega(j) * as_ / ts_;
    }
    *out = column;
  }

  // The platform column of a board at velocity v: its contact mode when its law is set-valued
  // (`mode`, -1, 0, 1), else the sign of v.
  static int column(bool set_valued, int mode, double v) {
    if (set_valued) return mode;
    return v > 0 ? 1 : (v < 0 ? -1 : 0);
  }

 private:
  std::vector<int> pendulum_;
  double xs_ = 1.0, as_ = 1.0, ts_ = 1.0;  // per SI unit: x, angle, time
};

}  // namespace metrosync
