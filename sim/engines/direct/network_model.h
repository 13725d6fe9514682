// A network of platforms as the direct run's model (sim/engines/direct/direct_run.h): the
// network's minimal coordinates (models/network_equations.h), one view per platform for the shared
// resolver (its pendulums, the contact under it), and its state on the sample grid for the sink.
// A tick moves only its own platform directly; a platform resting on one that a tick moved settles
// after it (the run's settleSupports). Witnesses are checked at every step end and located on the
// dense output (a crossing and its return within one step, a graze, is not seen: steps are at
// most kMaxStepPeriods of a period).
#pragma once

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "contact/escapement.h"
#include "contact/platform_friction.h"
#include "models/network.h"
#include "models/network_equations.h"
#include "sim/events/event_system.h"
#include "sim/ode/rk_stepper.h"
#include "sim/ode/rk_tableau.h"
#include "sim/record/failure_text.h"
#include "sim/record/run_report.h"
#include "sim/record/split_timer.h"

namespace metrosync::direct {

// The longest step, in fast periods: short enough that a witness cannot cross and return within
// one step for any amplitude the escapement sustains (a tick witness stays above zero for about a
// tenth of a period; a stuck contact's margin has no closed-form rate here), long enough to cost
// nothing when the accuracy sets the step.
constexpr double kMaxStepPeriods = 0.05;

class NetworkRhs : public ode::OdeRhs {
 public:
  NetworkRhs(const network::NetworkEquations& eq, const std::vector<PlatformMode>& modes)
      : eq_(eq), modes_(modes) {}
  void eval(const double* y, double* dy) override { eq_.rhs(y, modes_, dy); }

 private:
  const network::NetworkEquations& eq_;
  const std::vector<PlatformMode>& modes_;
};

// One platform seen by the shared resolver: its pendulums, the contact under it, on the state the
// window resolves (bound by the run).
class PlatformView : public EventSystem {
 public:
  PlatformView(const network::NetworkEquations& eq, std::vector<PlatformMode>& modes, int p,
               long& rows)
      : eq_(eq), modes_(modes), p_(p), rows_(rows) {}
  void bind(double* y) { y_ = y; }
  int first() const { return eq_.block(p_).first; }
  double theta(int j) const override { return y_[eq_.layout().theta(first() + j)]; }
  double thetadot(int j) const override { return y_[eq_.layout().omega(first() + j)]; }
  double xdot() const override { return eq_.slipVelocity(y_, p_); }
  PlatformMode mode() const override { return modes_[p_]; }
  void setMode(PlatformMode m) override { modes_[p_] = m; }
  double holdingForce() override { return eq_.holdingForces(y_, modes_)[p_]; }
  double applyImpulse(const std::vector<double>& pin_impulse, double platform_impulse) override {
    std::vector<double> pin(eq_.layout().n, 0.0), contact(eq_.numPlatforms(), 0.0);
    std::copy(pin_impulse.begin(), pin_impulse.end(), pin.begin() + first());
    contact[p_] = platform_impulse;
    return eq_.applyImpulse(y_, pin, contact);
  }
  double platformMobility() override { return eq_.contactMobility(y_, p_); }
  void eventRow(const char*) override { ++rows_; }

 private:
  const network::NetworkEquations& eq_;
  double* y_ = nullptr;
  std::vector<PlatformMode>& modes_;
  int p_;
  long& rows_;
};

// The network as the run's model (sim/engines/direct/direct_run.h): its minimal coordinates, one
// view per platform, and its state on the sample grid for the sink (the last at t_end exactly).
// A network counts as its events the windows and every row the resolvers would write (as the
// Simbody engine's network recorder does).
class NetworkModel {
 public:
  using Stepper = ode::RkStepper;
  static constexpr bool kHoldingForceRate = false;
  NetworkModel(SplitTimer& timer, const Network& net, RunSink& sink);

  Stepper& stepper() { return stepper_; }
  const ode::RkTableau& tableau() const { return tab_; }
  const network::Layout& layout() const { return lay_; }
  int platforms() const { return lay_.platforms; }
  int first(int p) const { return eq_.block(p).first; }
  int count(int p) const { return eq_.block(p).count; }
  int below(int p) const { return eq_.block(p).below; }
  bool moves(int p) const { return eq_.block(p).moves; }
  int rigIndex(int j) const { return eq_.pendulum(j).rig_index; }
  const PlatformFriction& contact(int p) const { return contacts_[p]; }
  Escapement escapement(int j) const { return eq_.escapement(j); }
  PlatformMode mode(int p) const { return modes_[p]; }
  double slipVelocity(int p, const double* y) const { return eq_.slipVelocity(y, p); }
  double holdingForce(int p, const double* y) const { return eq_.holdingForces(y, modes_)[p]; }
  EventSystem& view(int p, double* y, double) {
    views_[p]->bind(y);
    return *views_[p];
  }
  double period() const { return period_; }
  double maxStepSize() const { return kMaxStepPeriods * period_; }
  double accuracy() const { return net_.sim.accuracy; }
  double tEnd() const { return net_.sim.t_end_s; }
  double energy(const double* y) const { return eq_.energy(y); }
  double dampingOut(const double* y) const { return y[lay_.dampingWork()] + lay_.damperWorkIn(y); }
  std::vector<double> startState() const;
  int metronomes() const { return net_.numMetronomes(); }
  std::string failureText(double t, const std::string& why) const {
    return metrosync::failureText(t, why);
  }

  // --- recording: the state on the grid ---------------------------------------------------
  void start(const double* y) {
    sample(0.0, y);
    next_sample_ = 1;
  }
  void samplesBefore(Stepper& s, double t_limit, bool inclusive);
  void window(const double*, double) {}
  void last(const double* y, double t, RunReport& r) {
    r.final_state.assign(y, y + lay_.dim());
    sample(t, y);
  }
  void close(RunReport& r) const { r.counts.events += rows_; }

 private:
  void sample(double t, const double* y);

  SplitTimer& timer_;
  const Network& net_;
  RunSink& sink_;
  network::NetworkEquations eq_;
  network::Layout lay_;
  std::vector<PlatformMode> modes_;
  std::vector<PlatformFriction> contacts_;  // the set-valued law under a moving platform, or none
  NetworkRhs rhs_;
  const ode::RkTableau& tab_;
  ode::RkStepper stepper_;
  std::vector<std::unique_ptr<PlatformView>> views_;
  std::vector<double> scratch_, row_;
  double period_ = 1.0, sample_dt_ = 1.0;
  long next_sample_ = 0;
  long rows_ = 0;  // the event rows of every window
};

}  // namespace metrosync::direct
