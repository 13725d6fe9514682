// The flow of one smooth piece of an orbit -- between two event windows, in one platform mode --
// with its linearization: z' = f(z), Phi' = Df(z) Phi, Phi (d x d) the sensitivity of z to the
// state at the start of the orbit (scaled variables, sim/analysis/periodic_orbit/scaled_model.h).
// The engine has decided where the pieces start and end (the event windows); this integrates in
// between with the same kind of stepper (Verner 7(6), sim/ode). Only z is under error control:
// the steps, and so z, are the same to the last bit whether or not Phi is carried along.
#pragma once

#include <memory>

#include "sim/analysis/periodic_orbit/scaled_model.h"
#include "sim/ode/rk_stepper.h"

namespace metrosync::orbit {

// Where a piece stands: the time, the state and (when carried) Phi.
struct FlowPoint {
  double t = 0.0;
  Vec z;
  Mat phi;  // empty when not carried
};

// The section of the return map: theta_r = 0 crossed upwards (theta_r' = thetadot_r > 0).
struct SectionSpec {
  int pendulum = 0;    // r, among the swinging pendulums
  double t_min = 0.0;  // crossings before this time are not returns
};

class PieceFlow {
 public:
  // accuracy: relative local error target of z (absolute in scaled units likewise)
  PieceFlow(const ScaledModel& model, double accuracy);
  ~PieceFlow();

  // Advances `at` to t1 in `mode`.
  void advance(FlowPoint& at, double t1, PlatformMode mode);
  // Advances `at` towards t1 in `mode`, stopping at the first upward crossing of the section
  // after section.t_min; true when it stopped there (at.z's theta_r is 0 to rounding).
  bool advanceToSection(FlowPoint& at, double t1, PlatformMode mode, const SectionSpec& section);

  long steps() const { return steps_; }

 private:
  struct Rhs;
  bool run(FlowPoint& at, double t1, PlatformMode mode, const SectionSpec* section);
  void restart(const FlowPoint& at, PlatformMode mode);
  double locateSection(int k, double step);
  void take(FlowPoint& at) const;

  const ScaledModel& model_;
  double accuracy_;
  std::unique_ptr<Rhs> rhs_z_, rhs_ext_;
  std::unique_ptr<ode::RkStepper> z_only_, extended_;
  ode::RkStepper* cur_ = nullptr;  // the stepper of the piece being integrated
  bool with_phi_ = false;
  long steps_ = 0;
};

}  // namespace metrosync::orbit
