#include "sim/engines/direct/network_engine.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include "base/constants.h"
#include "base/number_text.h"
#include "models/network_equations.h"
#include "sim/engines/direct/direct_engine.h"
#include "sim/engines/direct/start_state.h"
#include "sim/engines/direct/step_loop.h"
#include "sim/events/crossing.h"
#include "sim/events/resolver.h"
#include "sim/events/window.h"
#include "sim/events/witness.h"
#include "sim/events/witness_list.h"
#include "sim/ode/rk_stepper.h"
#include "sim/ode/rk_tableau.h"
#include "sim/ode/root_find.h"
#include "sim/record/split_timer.h"

namespace metrosync {

namespace {

using network::NetworkEquations;

// The longest step, in fast periods: short enough that a witness cannot cross and return within
// one step for any amplitude the escapement sustains (a tick witness stays above zero for about a
// tenth of a period), long enough to cost nothing when the accuracy sets the step.
constexpr double kMaxStepPeriods = 0.05;
// Resolution passes per event window: each pass settles the platforms whose support moved; a
// stack of P platforms needs at most P passes.
constexpr int kSettlePassesPerPlatform = 2;

class Rhs : public ode::OdeRhs {
 public:
  Rhs(const NetworkEquations& eq, const std::vector<PlatformMode>& modes)
      : eq_(eq), modes_(modes) {}
  void eval(const double* y, double* dy) override { eq_.rhs(y, modes_, dy); }

 private:
  const NetworkEquations& eq_;
  const std::vector<PlatformMode>& modes_;
};

// One platform seen by the shared resolver: its pendulums, the contact under it.
class ContactView : public EventSystem {
 public:
  ContactView(const NetworkEquations& eq, std::vector<double>& y, std::vector<PlatformMode>& modes,
              int p, long& rows)
      : eq_(eq), y_(y), modes_(modes), p_(p), rows_(rows) {}
  int first() const { return eq_.block(p_).first; }
  double theta(int j) const override { return y_[eq_.layout().theta(first() + j)]; }
  double thetadot(int j) const override { return y_[eq_.layout().omega(first() + j)]; }
  double xdot() const override { return eq_.slipVelocity(y_.data(), p_); }
  PlatformMode mode() const override { return modes_[p_]; }
  void setMode(PlatformMode m) override { modes_[p_] = m; }
  double holdingForce() override { return eq_.holdingForces(y_.data(), modes_)[p_]; }
  double applyImpulse(const std::vector<double>& pin_impulse, double platform_impulse) override {
    std::vector<double> pin(eq_.layout().n, 0.0), contact(eq_.numPlatforms(), 0.0);
    std::copy(pin_impulse.begin(), pin_impulse.end(), pin.begin() + first());
    contact[p_] = platform_impulse;
    return eq_.applyImpulse(y_.data(), pin, contact);
  }
  double platformMobility() override { return eq_.contactMobility(y_.data(), p_); }
  void eventRow(const char*) override { ++rows_; }

 private:
  const NetworkEquations& eq_;
  std::vector<double>& y_;
  std::vector<PlatformMode>& modes_;
  int p_;
  long& rows_;
};

class NetworkRun {
 public:
  NetworkRun(const Network& net, NetworkSink& sink);
  RunReport run();

  // --- the hooks of the run loop (sim/engines/direct/step_loop.h) ---------------------------
  ode::RkStepper& stepper() { return stepper_; }
  const double* mechanicalEnd(const double* y) const { return y + lay_.dampingWork(); }
  bool complete() const { return report_.complete; }
  void countStep() { ++report_.counts.steps; }
  bool findCrossings();
  void emitSamplesBefore(double t_limit, bool inclusive);
  void rearm(const double* y);
  double locateWindow();
  void resolveWindow(double t_e, double th_e);
  void fail(double t, const std::string& why);

  // --- witnesses: the model's side of the shared list (sim/events/witness_list.h) ------------
  bool armed(const RunWitness& w) const;
  std::optional<LinearForm> linearForm(const RunWitness& w) const;
  std::optional<WindowCrossing> detectStuck(int index, const RunWitness& w);
  double stuckValueAt(const RunWitness& w, double th);

 private:
  double witnessValue(const RunWitness& w, const double* y,
                      const std::vector<double>& lambda) const;
  void resolveContacts(double t_e, double th_e);
  void settleSupports();
  void absorb(const WindowOutcome& out, int p);
  void sample(double t, const std::vector<double>& y);
  void finish();

  const Network& net_;
  NetworkSink& sink_;
  NetworkEquations eq_;
  network::Layout lay_;
  std::vector<PlatformMode> modes_;
  Rhs rhs_;
  const ode::RkTableau& tab_;
  ode::RkStepper stepper_;
  std::vector<double> y_, scratch_;
  std::vector<std::unique_ptr<ContactView>> views_;
  std::vector<EventResolver> resolvers_;
  WitnessList witnesses_;
  RunReport report_;
  SplitTimer timer_;  // the engine's time against the recording's
  double period_ = 1.0, sample_dt_ = 1.0, t_end_ = 0.0;
  double last_window_t_ = -1.0;  // time of the last resolved window
  // two windows this close (in ulps of t) are one instant: the localization resolves no finer
  static constexpr double kSameInstantUlps = 16;
  long next_sample_ = 0;
};

NetworkRun::NetworkRun(const Network& net, NetworkSink& sink)
    : net_(net),
      sink_(sink),
      eq_(net),
      lay_(eq_.layout()),
      modes_(lay_.platforms, PlatformMode::Stuck),
      rhs_(eq_, modes_),
      tab_(ode::rkTableau(net.sim.integrator.empty() ? defaultDirectIntegrator(net.unionRig())
                                                     : net.sim.integrator)),
      stepper_(tab_, lay_.dim(), rhs_) {
  const Rig scales = net.unionRig();
  const ScaledParams sp = computeScaled(scales);
  period_ = kTwoPi * sp.time_scale_s;
  t_end_ = net.sim.t_end_s;
  sample_dt_ = net.sim.sample_s > 0 ? net.sim.sample_s : period_ / 20;
  report_.model = "full";
  report_.engine = "direct";
  report_.integrator = tab_.name;
  report_.accuracy = net.sim.accuracy;
  report_.has_ledger = true;
  report_.fast_period_s = period_;
  report_.counts.escapements.assign(net.numMetronomes(), 0);
  y_.assign(lay_.dim(), 0.0);
  for (int p = 0; p < lay_.platforms; ++p) {
    const network::Block& b = eq_.block(p);
    direct::writePlatformStart(net.platforms[p].rig, b.moves, lay_, p, b.first, y_.data());
    for (int k = b.first; k < b.first + b.count; ++k)
      if (eq_.escapement(k).active()) witnesses_.addTicks(k);
    const bool set_valued = b.moves && b.friction.setValued();
    if (set_valued) witnesses_.addContact(p);
    resolvers_.push_back(direct::startResolver(
        lay_, y_.data(), b.first, b.count, [&](int k) { return eq_.escapement(k); },
        set_valued ? b.friction : PlatformFriction{}, period_));
    views_.push_back(std::make_unique<ContactView>(eq_, y_, modes_, p, report_.counts.events));
  }
  stepper_.setTolerances(net.sim.accuracy, direct::scaledTolerances(net.sim.accuracy, sp, lay_));
}

double NetworkRun::witnessValue(const RunWitness& w, const double* y,
                                const std::vector<double>& lambda) const {
  if (w.tick()) {
    return TickWitness{w.index, w.side}.value(eq_.escapement(w.index), y[lay_.theta(w.index)]);
  }
  const network::Block& b = eq_.block(w.index);
  const double g = PlatformWitness::value(b.friction.dry, modes_[w.index],
                                          eq_.slipVelocity(y, w.index), lambda[w.index]);
  return risingSign(PlatformWitness::kDirection) * g;
}

bool NetworkRun::armed(const RunWitness& w) const {
  int p = 0;  // the platform of pendulum w.index: its resolver numbers its pendulums from 0
  while (w.index >= eq_.block(p).first + eq_.block(p).count) ++p;
  return resolvers_[p].armed(w.index - eq_.block(p).first, w.side);
}

// A tick on its angle, a slipping contact on its slip velocity against the platform below.
std::optional<LinearForm> NetworkRun::linearForm(const RunWitness& w) const {
  if (w.tick())
    return LinearForm{lay_.theta(w.index), -1, static_cast<double>(w.side),
                      eq_.escapement(w.index).theta_c};
  const int p = w.index;
  if (modes_[p] == PlatformMode::Stuck) return std::nullopt;
  const int below = eq_.block(p).below;
  return LinearForm{lay_.v(p), below < 0 ? -1 : lay_.v(below),
                    -static_cast<double>(static_cast<int>(modes_[p])), 0.0};
}

// A stuck contact's margin on the dense output: a function of the whole state (the holding
// forces of every stuck contact).
double NetworkRun::stuckValueAt(const RunWitness& w, double th) {
  stepper_.interpolate(th, scratch_.data());
  return witnessValue(w, scratch_.data(), eq_.holdingForces(scratch_.data(), modes_));
}

// A stuck contact's crossing: the sign change of its margin between the step's ends (its rate has
// no closed form here).
std::optional<WindowCrossing> NetworkRun::detectStuck(int index, const RunWitness& w) {
  auto margin = [&](const double* y) { return witnessValue(w, y, eq_.holdingForces(y, modes_)); };
  auto value_at = [&](double th) { return stuckValueAt(w, th); };
  auto no_rates = [] { return std::optional<std::pair<double, double>>(); };
  return detectMargin(index, margin(stepper_.y()), margin(stepper_.y1()), no_rates, value_at,
                      [](double) { return 0.0; });
}

bool NetworkRun::findCrossings() {
  return witnesses_.findCrossings(stepper_, *this, [](const RunWitness&) { return true; });
}

// The escapements re-armed on the state y (the kept step's end: y_ follows it).
void NetworkRun::rearm(const double* y) {
  std::copy(y, y + lay_.dim(), y_.begin());
  for (int p = 0; p < lay_.platforms; ++p) resolvers_[p].rearm(*views_[p]);
}

// The window (sim/events/window.h): every crossing bracketed, the end at the earliest.
double NetworkRun::locateWindow() {
  return metrosync::locateWindow(witnesses_.found(), [&](int w, double th) {
    return witnesses_.valueAt(stepper_, *this, w, th);
  });
}

// The window's end state in y_, resolved; the escapements re-armed on the result, the stepper
// restarted from it.
void NetworkRun::resolveWindow(double t_e, double th_e) {
  stepper_.interpolate(th_e, y_.data());
  resolveContacts(t_e, th_e);
  for (int p = 0; p < lay_.platforms; ++p) resolvers_[p].rearm(*views_[p]);
  stepper_.restart(t_e, y_.data());
}

void NetworkRun::absorb(const WindowOutcome& out, int p) {
  report_.ledger.escapement_in_J += out.escapement_in;
  report_.ledger.friction_out_J += out.friction_out;
  report_.counts.stick_slip += out.stick_slip;
  report_.counts.slip_reversals += out.slip_reversals;
  for (int j : out.ticked)
    ++report_.counts.escapements[eq_.pendulum(eq_.block(p).first + j).rig_index];
}

// Platforms whose contact the window's later changes left inconsistent: stuck with a velocity (an
// impulse below them), stuck beyond the bound (another contact's switch or tick changed the
// forces on it after its own rule was applied: left so, its witness would start below zero and
// never cross), or slipping against their mode.
void NetworkRun::settleSupports() {
  for (int pass = 0; pass < kSettlePassesPerPlatform * lay_.platforms; ++pass) {
    bool changed = false;
    for (int p = 0; p < lay_.platforms; ++p) {
      const network::Block& b = eq_.block(p);
      if (!b.moves || !b.friction.setValued()) continue;
      const double u = eq_.slipVelocity(y_.data(), p);
      const bool off =
          modes_[p] == PlatformMode::Stuck
              ? u != 0 || b.friction.dry.breaksFree(eq_.holdingForces(y_.data(), modes_)[p])
              : static_cast<int>(modes_[p]) * u <= 0;
      if (!off) continue;
      const WindowOutcome out = resolvers_[p].settleAfterSupportImpulse(*views_[p]);
      absorb(out, p);
      changed = true;
    }
    if (!changed) return;
  }
}

// The window's end state in y_: each platform's resolver acts in file order; its contact reports
// when its witness has crossed (the stick margins judged on the window's state before any
// impulse, the slip velocities when the platform's turn comes: an earlier platform's tick may
// have moved the one below it) or when its slip was stopped where it could not get going.
void NetworkRun::resolveContacts(double t_e, double th_e) {
  const std::vector<double> lambda = eq_.holdingForces(y_.data(), modes_);
  std::vector<char> forced(lay_.platforms, 0);
  for (const WindowCrossing& c : witnesses_.found())
    if (c.forced && c.th.hi <= th_e) forced[witnesses_[c.witness].index] = 1;
  for (int p = 0; p < lay_.platforms; ++p) {
    bool reported = forced[p];
    for (int i = 0; i < witnesses_.size(); ++i) {
      const RunWitness& w = witnesses_[i];
      if (!w.tick() && w.index == p) reported = reported || witnessValue(w, y_.data(), lambda) >= 0;
    }
    absorb(resolvers_[p].resolve(*views_[p], reported), p);
  }
  settleSupports();
  // a window that follows the last one within the localization's resolution (a few ulps of t: a
  // contact left just past its witness by the last window's impulses, found again at the
  // restart) is that window continued, not a new one (sim/events/window.h: one window per
  // instant)
  if (!(t_e - last_window_t_ <= kSameInstantUlps * std::numeric_limits<double>::epsilon() * t_e))
    ++report_.counts.events;
  last_window_t_ = t_e;
}

// The samples on the grid (simulation.sample) in the current step before t_limit (or at it, if
// inclusive), strictly before t_end: the run's last sample is its final state, at t_end exactly.
void NetworkRun::emitSamplesBefore(double t_limit, bool inclusive) {
  const double t0 = stepper_.t(), h = stepper_.h();
  for (;;) {
    const double ts = next_sample_ * sample_dt_;
    if (ts >= t_end_ || ts > t_limit || (!inclusive && ts == t_limit)) return;
    stepper_.interpolate(h > 0 ? (ts - t0) / h : 0.0, scratch_.data());
    sample(ts, scratch_);
    ++next_sample_;
  }
}

void NetworkRun::sample(double t, const std::vector<double>& y) {
  RecordingScope rec(timer_);
  sink_.sample(t, y, modes_);
}

void NetworkRun::fail(double t, const std::string& why) {
  report_.complete = false;
  report_.failure = "at t = " + numberText(t, 6, Notation::Fixed) + " s: " + why;
}

RunReport NetworkRun::run() {
  timer_ = SplitTimer();
  scratch_.resize(lay_.dim());
  for (int p = 0; p < lay_.platforms; ++p)
    if (eq_.block(p).moves && eq_.block(p).friction.setValued())
      resolvers_[p].settleAtStart(*views_[p]);
  report_.ledger.initial_J = eq_.energy(y_.data());
  sample(0.0, y_);
  next_sample_ = 1;
  stepper_.restart(0.0, y_.data());
  const double h_max = kMaxStepPeriods * period_;
  StormGuard storm(period_, StormGuard::kMaxEvents, StormGuard::kWindowPeriods);
  direct::integrateTo(*this, t_end_,
                      direct::firstStepSize(h_max, period_, net_.sim.accuracy, tab_.order), h_max,
                      period_, storm);
  finish();
  return report_;
}

// The run's last sample: its final state, at t_end exactly when complete (the last step ends
// there: t_end - t is exact for t >= t_end / 2), else where it stopped; the report's totals.
void NetworkRun::finish() {
  report_.t_end = report_.complete ? t_end_ : stepper_.t();
  sample(report_.t_end, y_);
  report_.counts.rhs_evals = stepper_.evaluations();
  report_.final_state = y_;
  report_.ledger.final_J = eq_.energy(y_.data());
  report_.ledger.damping_out_J = y_[lay_.dampingWork()] + y_[lay_.damperWork()];
  report_.ledger.friction_out_J += y_[lay_.frictionWork()];
  report_.wall_seconds = timer_.wallSeconds();
  report_.engine_seconds = report_.wall_seconds - timer_.recordingSeconds(report_.wall_seconds);
}

}  // namespace

RunReport runNetworkDirect(const Network& net, NetworkSink& sink) {
  return NetworkRun(net, sink).run();
}

}  // namespace metrosync
