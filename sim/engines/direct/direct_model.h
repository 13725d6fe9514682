// The direct run's one model (sim/engines/direct/direct_run.h; issue 38: a board is a network of
// one): a rig's minimal coordinates (models/network_equations.h), one view per platform for the
// shared resolver (its pendulums, the contact under it), and its files. Its kind K is what the
// compiler knows (model_dynamics.h): a single board -- one platform on the table, no damper, no
// coupling (Network::isSingleRig) -- with N swinging pendulums (1 .. kMaxFixedN, or kAnyN), or a
// network (kNetwork). What the kinds do differently, each for its reason:
//   equations   a single board's fused entry with one mode; a network's general equations
//   holding     a single board's closed form with its rate (a grazing margin is found); a
//               network's one solve over its stuck contacts, without a rate, so its steps are at
//               most kMaxStepPeriods of a period (a margin cannot cross and return in one)
//   files       a single board's rig files (rig_recording.h: rows, envelope, events, in the rig's
//               units); a network's states on the sample grid (state_samples.h)
//   a stop      a single board's stuck platform holds xdot = 0 exactly (the residual of a stop)
//   failure     a single board's time in scaled units too when its rig is scaled
// The sink never chooses the kind: the rig's shape does.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "base/constants.h"
#include "contact/escapement.h"
#include "contact/platform_friction.h"
#include "models/network.h"
#include "models/network_equations.h"
#include "models/rig.h"
#include "models/scaling.h"
#include "sim/engines/direct/direct_integrators.h"
#include "sim/engines/direct/model_dynamics.h"
#include "sim/engines/direct/rig_recording.h"
#include "sim/engines/direct/start_state.h"
#include "sim/engines/direct/state_samples.h"
#include "sim/events/event_system.h"
#include "sim/ode/rk_tableau.h"
#include "sim/record/failure_text.h"
#include "sim/record/run_report.h"
#include "sim/record/split_timer.h"

namespace metrosync::direct {

// A network's longest step, in fast periods: short enough that a witness cannot cross and return
// within one step for any amplitude the escapement sustains (a tick witness stays above zero for
// about a tenth of a period; a stuck contact's margin has no closed-form rate here), long enough
// to cost nothing when the accuracy sets the step.
constexpr double kMaxStepPeriods = 0.05;

// Internal linkage on purpose (this header has one includer, direct_engine.cpp): the run's
// instantiation over a model of internal linkage is itself internal, so the compiler inlines the
// run's hooks into the step loop as it did when the run lived in that file. With external
// linkage the same run executed 2.8% more instructions (valgrind, peer-n2 at 1e-5:
// tools/bench/instructions.sh; 49.8M against 50.4M for the probe's three runs).
namespace {

template <int K>
class DirectModel;

// Platform p seen by the shared resolver, on the state the window resolves (bound by the model).
template <int K>
class PlatformView final : public EventSystem {
 public:
  PlatformView(DirectModel<K>& m, int p) : m_(m), p_(p), first_(m.first(p)) {}
  void bind(double* y, double t) {
    y_ = y;
    t_ = t;
    mobility_ = 0.0;
  }
  double theta(int j) const override { return y_[m_.layout().theta(first_ + j)]; }
  double thetadot(int j) const override { return y_[m_.layout().omega(first_ + j)]; }
  double xdot() const override { return m_.slipVelocity(p_, y_); }
  PlatformMode mode() const override { return m_.mode(p_); }
  void setMode(PlatformMode mode) override {
    m_.dyn_.set(p_, mode);
    if constexpr (singleBoard(K))
      if (mode == PlatformMode::Stuck) y_[m_.layout().v(0)] = 0.0;  // the residual of a stop
  }
  double holdingForce() override { return m_.holdingForce(p_, y_); }
  double applyImpulse(const std::vector<double>& pin, double platform) override {
    if constexpr (singleBoard(K)) {
      return m_.eq_.applyImpulse(y_, pin.data(), platform);
    } else {
      std::vector<double> all(m_.layout().n, 0.0), contact(m_.platforms(), 0.0);
      std::copy(pin.begin(), pin.end(), all.begin() + first_);
      contact[p_] = platform;
      return m_.eq_.applyImpulse(y_, all, contact);
    }
  }
  // the angles do not change while a window is resolved: one evaluation per window
  double platformMobility() override {
    if (!(mobility_ > 0))
      mobility_ = singleBoard(K) ? m_.eq_.platformMobility(y_) : m_.eq_.contactMobility(y_, p_);
    return mobility_;
  }
  void eventRow(const char* kind) override { m_.rec_.eventRow(kind, y_, t_, mode()); }
  void snapshotBefore() override { m_.rec_.snapshot(y_, t_, mode()); }
  void recordEvent(const char* kind, int j) override {
    m_.rec_.eventRecord(kind, j < 0 ? j : first_ + j, y_, t_, mode());
  }

 private:
  DirectModel<K>& m_;
  int p_, first_;
  double* y_ = nullptr;
  double t_ = 0.0;
  double mobility_ = 0.0;  // platformMobility() at y_'s angles (0: not computed yet)
};

template <int K>
class DirectModel {
 public:
  static constexpr bool kSingle = singleBoard(K);
  using Stepper = ModelStepper<K>;
  using Recording = std::conditional_t<kSingle, RigRecording<K>, StateSamples>;
  using Layout = std::conditional_t<kSingle, network::BoardLayout, network::Layout>;
  static constexpr bool kHoldingForceRate = kSingle;  // closed form on a single board
  // `net` a network (kNetwork) or a single rig's network of one, `rig` its rig (kSingle)
  DirectModel(SplitTimer& timer, const Network& net, const Rig& rig, RunSink& sink);

  // --- the model (sim/engines/direct/direct_run.h) ----------------------------------------------
  Stepper& stepper() { return stepper_; }
  const ode::RkTableau& tableau() const { return tab_; }
  const Layout& layout() const { return lay_; }
  // (a single board's known to the compiler: the run's loops over platforms and pendulums fold)
  int platforms() const { return kSingle ? 1 : lay_.platforms; }
  int first(int p) const { return kSingle ? 0 : eq_.block(p).first; }
  int count(int p) const { return kSingle ? lay_.n : eq_.block(p).count; }
  int below(int p) const { return kSingle ? -1 : eq_.block(p).below; }
  bool moves(int p) const { return eq_.block(kSingle ? 0 : p).moves; }
  int rigIndex(int j) const { return eq_.pendulum(j).rig_index; }
  const PlatformFriction& contact(int p) const { return contacts_[kSingle ? 0 : p]; }
  Escapement escapement(int j) const { return eq_.escapement(j); }
  PlatformMode mode(int p) const { return dyn_.of(p); }
  double slipVelocity(int p, const double* y) const {
    return kSingle ? y[lay_.v(0)] : eq_.slipVelocity(y, p);
  }
  double holdingForce(int p, const double* y) const {
    if constexpr (kSingle)
      return eq_.holdingForce(y);
    else
      return eq_.holdingForces(y, dyn_.modes)[p];
  }
  double holdingForceRate(int, const double* y) const { return eq_.holdingForceRate(y); }
  EventSystem& view(int p, double* y, double t) {
    views_[p]->bind(y, t);
    return *views_[p];
  }
  double period() const { return period_; }
  double maxStepSize() const;
  double accuracy() const { return net_.sim.accuracy; }
  double tEnd() const { return net_.sim.t_end_s; }
  double energy(const double* y) const { return eq_.energy(y); }
  double dampingOut(const double* y) const { return y[lay_.dampingWork()] + lay_.damperWorkIn(y); }
  std::vector<double> startState() const;
  int metronomes() const { return net_.numMetronomes(); }
  std::string failureText(double t, const std::string& why) const {
    if constexpr (kSingle)
      return metrosync::failureText(t, why, &sp_, rig_.units == Units::Scaled);
    else
      return metrosync::failureText(t, why);
  }

  // --- recording ------------------------------------------------------------------------------
  void start(const double* y) { rec_.start(y, dyn_.recorded()); }
  void samplesBefore(Stepper& s, double t_limit, bool inclusive) {
    rec_.samplesBefore(s, t_limit, inclusive, dyn_.recorded());
  }
  void window(const double*, double) {}  // each step's stretch ends at the window: nothing more
  void last(const double* y, double t, RunReport& r) {
    r.final_state.assign(y, y + lay_.dim());
    rec_.last(y, t, dyn_.recorded(), r);
  }
  void close(RunReport& r) { rec_.close(r); }

 private:
  friend class PlatformView<K>;
  const Network& net_;
  const Rig& rig_;
  ScaledParams sp_;
  network::NetworkEquations eq_;
  Layout lay_;
  Dynamics<K> dyn_;
  std::vector<PlatformFriction> contacts_;  // the set-valued law under a moving platform, or none
  const ode::RkTableau& tab_;
  Stepper stepper_;
  double period_ = 1.0;
  Recording rec_;
  std::vector<std::unique_ptr<PlatformView<K>>> views_;

  Recording makeRecording(SplitTimer& timer, RunSink& sink);
};

// The rig whose scales (fast period, tolerances) and default integrator a run takes: a single
// board's own rig; a network's union (models/network.h).
inline Rig scalesOf(const Network& net, const Rig& rig, bool single) {
  return single ? rig : net.unionRig();
}

template <int K>
DirectModel<K>::DirectModel(SplitTimer& timer, const Network& net, const Rig& rig, RunSink& sink)
    : net_(net),
      rig_(rig),
      sp_(computeScaled(scalesOf(net, rig, kSingle))),
      eq_(net),
      lay_(eq_.layout().template as<Layout{}.platforms>()),
      dyn_(eq_, lay_.platforms),
      tab_(ode::rkTableau(net.sim.integrator.empty()
                              ? defaultDirectIntegrator(scalesOf(net, rig, kSingle))
                              : net.sim.integrator)),
      stepper_(tab_, lay_.dim(), dyn_),
      // (a single board's as its rig's model always had it: 2 pi over omega0)
      period_(kSingle ? kTwoPi / (1.0 / sp_.time_scale_s) : kTwoPi * sp_.time_scale_s),
      rec_(makeRecording(timer, sink)) {
  for (int p = 0; p < lay_.platforms; ++p) {
    const network::Block& b = eq_.block(p);
    contacts_.push_back(b.moves && b.friction.setValued() ? b.friction : PlatformFriction{});
    views_.push_back(std::make_unique<PlatformView<K>>(*this, p));
  }
  stepper_.setTolerances(net.sim.accuracy, scaledTolerances(net.sim.accuracy, sp_, lay_));
}

template <int K>
typename DirectModel<K>::Recording DirectModel<K>::makeRecording(SplitTimer& timer, RunSink& sink) {
  if constexpr (kSingle)
    return Recording(timer, rig_, sp_, sink, period_);
  else
    return Recording(timer, sink, net_.sim.sample_s, period_, net_.sim.t_end_s, lay_.dim());
}

// Every platform's start state (the run arms its resolvers and settles the contacts' modes on it).
template <int K>
std::vector<double> DirectModel<K>::startState() const {
  std::vector<double> y(lay_.dim(), 0.0);
  for (int p = 0; p < lay_.platforms; ++p) {
    const network::Block& b = eq_.block(p);
    writePlatformStart(net_.platforms[p].rig, b.moves, lay_, p, b.first, y.data());
  }
  return y;
}

// The largest step. A single board: a fraction of the fastest oscillation (pendulums, platform
// spring), so that a step holds at most one extreme of any witness. A network: kMaxStepPeriods.
template <int K>
double DirectModel<K>::maxStepSize() const {
  if constexpr (!kSingle) return kMaxStepPeriods * period_;
  double fastest = period_;
  for (int j = 0; j < lay_.n; ++j) {
    const network::PendulumConstants& p = eq_.pendulum(j);
    fastest = std::min(fastest, kTwoPi * std::sqrt(p.inertia / p.mgL));
  }
  if (eq_.hasPlatform() && rig_.platform.spring_N_m > 0) {
    double meff = eq_.totalMass();
    for (int j = 0; j < lay_.n; ++j)
      meff -= eq_.pendulum(j).mL * eq_.pendulum(j).mL / eq_.pendulum(j).inertia;
    fastest = std::min(fastest, kTwoPi * std::sqrt(meff / rig_.platform.spring_N_m));
  }
  return fastest / 10;
}

}  // namespace
}  // namespace metrosync::direct
