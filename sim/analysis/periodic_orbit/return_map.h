// The return map of the full model on a Poincare section (section.h): from u on the section, the
// direct engine runs the orbit (traceFrom: it decides every event), the smooth pieces between its
// windows are integrated again with their variational equations (piece_flow.h) and joined by the
// windows' saltation matrices (saltation.h), up to the first upward return to the section. That
// gives P(u), the return time (the period at a fixed point) and dP/du.
//
// A start on a stuck platform (xdot = 0 exactly, held by friction) has a perturbation of xdot
// stopped by friction at once: the sensitivity starts as the plastic stop's Jacobian there.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "models/rig.h"
#include "sim/analysis/periodic_orbit/engine_trace.h"
#include "sim/analysis/periodic_orbit/scaled_model.h"
#include "sim/analysis/periodic_orbit/section.h"

namespace metrosync::orbit {

// The orbit cannot be followed: the engine failed, or it does not come back to the section.
struct OrbitFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct ReturnSettings {
  // Relative local error target of the engine and of the pieces: 1e-12 leaves the return map's
  // noise (~1e-12 over a period) two orders below the orbit's Newton tolerance (1e-10).
  double accuracy = 1e-12;
  // The engine runs this many period guesses: the return lies near one (within O(epsilon)).
  double reach = 1.5;
  // A return needs this fraction of the period guess: the start itself (theta_r = 0 rising) and
  // rounding just below it are not returns.
  double min_fraction = 0.25;
};

// One pass from the section back to it.
struct Pass {
  Vec z0, z1;           // the start and the return, scaled (d x 1)
  Vec u0, u1;           // their section coordinates
  double period = 0.0;  // the return time (scaled)
  Mat jacobian;         // dP/du (dim x dim), when asked for
  Mat phi;              // dz(T)/dz(0) before the section's correction (d x d), when asked for
  PlatformMode start_mode = PlatformMode::Stuck, end_mode = PlatformMode::Stuck;
  std::vector<EngineWindow> windows;  // the event windows in (0, period)
  // the largest |z| difference between a piece's end and the engine's state before the window:
  // both integrate the same equations, so a mismatch far above the accuracy is a bug
  double mismatch = 0.0;
};

class ReturnMap {
 public:
  // `rig`: the parameters (its start and duration are not used); `pendulum`: the section's r.
  ReturnMap(const Rig& rig, int pendulum, const ReturnSettings& settings = {});

  const Rig& rig() const { return rig_; }
  const ScaledModel& model() const { return model_; }
  const Section& section() const { return section_; }
  const ReturnSettings& settings() const { return settings_; }

  // P(u) from the section state u; period_guess sets how far the engine runs. Throws
  // OrbitFailure.
  Pass pass(const Vec& u, double period_guess, bool with_jacobian) const;
  // The first upward crossing of the section from any state z (within `reach` of scaled time):
  // how a settled run's end state is put on the section. Throws OrbitFailure.
  Pass firstCrossing(const Vec& z, double reach) const;

 private:
  Pass around(const Vec& z0, double t_end, double t_min, bool with_jacobian) const;

  Rig rig_;
  ScaledModel model_;
  Section section_;
  ReturnSettings settings_;
};

}  // namespace metrosync::orbit
