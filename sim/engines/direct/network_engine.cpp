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
#include "sim/engines/direct/step_loop.h"
#include "sim/events/crossing.h"
#include "sim/events/resolver.h"
#include "sim/events/window.h"
#include "sim/events/witness.h"
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

// A witness, rising through zero at its event: a tick (pendulum j, side) or a contact (p).
struct Witness {
  bool tick = true;
  int index = 0;  // global pendulum (tick) or platform (contact)
  int side = 1;
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

 private:
  bool armed(const Witness& w) const;
  double witnessValue(const Witness& w, const double* y, const std::vector<double>& lambda) const;
  double witnessAt(const Witness& w, double th);
  std::optional<WindowCrossing> detect(int index);
  void resolveContacts(double t_e, double th_e);
  void settleSupports();
  void absorb(const WindowOutcome& out, int p);
  void sample(double t, const std::vector<double>& y);
  void finish();
  void setTolerances(const Rig& rig);

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
  std::vector<Witness> witnesses_;
  std::vector<WindowCrossing> found_;  // the crossings of the current step
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
    const NetworkPlatform& np = net.platforms[p];
    if (eq_.block(p).moves) {
      y_[lay_.x(p)] = np.rig.platform.start_x_m;
      y_[lay_.v(p)] = np.rig.platform.start_v_m_s;
    }
  }
  int j = 0;
  for (const NetworkPlatform& np : net.platforms)
    for (const MetronomeSpec& m : np.rig.metronomes) {
      if (m.locked) continue;
      y_[lay_.theta(j)] = m.start_angle_rad;
      y_[lay_.omega(j)] = m.start_rate_rad_s;
      ++j;
    }
  for (int p = 0; p < lay_.platforms; ++p) {
    const network::Block& b = eq_.block(p);
    std::vector<Escapement> esc;
    std::vector<double> th0;
    for (int k = b.first; k < b.first + b.count; ++k) {
      esc.push_back(eq_.escapement(k));
      th0.push_back(y_[lay_.theta(k)]);
      if (eq_.escapement(k).active())
        for (int side : {-1, 1}) witnesses_.push_back({true, k, side});
    }
    const bool set_valued = b.moves && b.friction.setValued();
    if (set_valued) witnesses_.push_back({false, p, 0});
    resolvers_.emplace_back(esc, set_valued ? b.friction : PlatformFriction{}, period_, th0);
    views_.push_back(std::make_unique<ContactView>(eq_, y_, modes_, p, report_.counts.events));
  }
  setTolerances(scales);
}

void NetworkRun::setTolerances(const Rig& rig) {
  // as the direct engine: errors in the scaled variables' units (s2.1), quadratures uncontrolled
  const ScaledParams sp = computeScaled(rig);
  const double acc = net_.sim.accuracy, omega0 = 1.0 / sp.time_scale_s;
  std::vector<double> atol(lay_.dim(), -1.0);
  for (int p = 0; p < lay_.platforms; ++p) {
    atol[lay_.x(p)] = acc * sp.x_scale_m;
    atol[lay_.v(p)] = acc * sp.x_scale_m * omega0;
  }
  for (int j = 0; j < lay_.n; ++j) {
    atol[lay_.theta(j)] = acc * sp.angle_scale;
    atol[lay_.omega(j)] = acc * sp.angle_scale * omega0;
  }
  stepper_.setTolerances(acc, atol);
}

double NetworkRun::witnessValue(const Witness& w, const double* y,
                                const std::vector<double>& lambda) const {
  if (w.tick) {
    return TickWitness{w.index, w.side}.value(eq_.escapement(w.index), y[lay_.theta(w.index)]);
  }
  const network::Block& b = eq_.block(w.index);
  const double g = PlatformWitness::value(b.friction.dry, modes_[w.index],
                                          eq_.slipVelocity(y, w.index), lambda[w.index]);
  return risingSign(PlatformWitness::kDirection) * g;
}

bool NetworkRun::armed(const Witness& w) const {
  int p = 0;  // the platform of pendulum w.index: its resolver numbers its pendulums from 0
  while (w.index >= eq_.block(p).first + eq_.block(p).count) ++p;
  return resolvers_[p].armed(w.index - eq_.block(p).first, w.side);
}

// A witness on the current step's dense output (rising through zero at its event).
double NetworkRun::witnessAt(const Witness& w, double th) {
  if (w.tick)  // one component of the dense output: O(1), whatever the network's size
    return TickWitness{w.index, w.side}.value(eq_.escapement(w.index),
                                              stepper_.component(lay_.theta(w.index), th));
  stepper_.interpolate(th, scratch_.data());
  return witnessValue(w, scratch_.data(), eq_.holdingForces(scratch_.data(), modes_));
}

// The crossing of witness `index` in the accepted step (sim/events/crossing.h, as the
// single-platform engine's): a tick on its angle, a slipping contact on its slip velocity (a slip
// that started from rest included), a stuck contact's margin by the sign change of its ends.
std::optional<WindowCrossing> NetworkRun::detect(int index) {
  const Witness& w = witnesses_[index];
  if (w.tick) {
    if (!armed(w)) return std::nullopt;
    return detectLinear(
        LinearWitness(stepper_, lay_.theta(w.index), w.side, eq_.escapement(w.index).theta_c),
        index, false);
  }
  const int p = w.index;
  if (modes_[p] != PlatformMode::Stuck) {
    const int below = eq_.block(p).below;
    return detectLinear(LinearWitness(stepper_, lay_.v(p), -static_cast<int>(modes_[p]), 0.0,
                                      below < 0 ? -1 : lay_.v(below)),
                        index, true);
  }
  auto margin = [&](const double* y) { return witnessValue(w, y, eq_.holdingForces(y, modes_)); };
  auto value_at = [&](double th) {
    stepper_.interpolate(th, scratch_.data());
    return margin(scratch_.data());
  };
  auto no_rates = [] { return std::optional<std::pair<double, double>>(); };
  return detectMargin(index, margin(stepper_.y()), margin(stepper_.y1()), no_rates, value_at,
                      [](double) { return 0.0; });
}

bool NetworkRun::findCrossings() {
  found_.clear();
  for (int i = 0; i < static_cast<int>(witnesses_.size()); ++i)
    if (auto c = detect(i)) found_.push_back(*c);
  return !found_.empty();
}

// The escapements re-armed on the state y (the kept step's end: y_ follows it).
void NetworkRun::rearm(const double* y) {
  std::copy(y, y + lay_.dim(), y_.begin());
  for (int p = 0; p < lay_.platforms; ++p) resolvers_[p].rearm(*views_[p]);
}

// The window (sim/events/window.h): every crossing bracketed, the end at the earliest.
double NetworkRun::locateWindow() {
  return metrosync::locateWindow(found_,
                                 [&](int w, double th) { return witnessAt(witnesses_[w], th); });
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
  for (const WindowCrossing& c : found_)
    if (c.forced && c.th.hi <= th_e) forced[witnesses_[c.witness].index] = 1;
  for (int p = 0; p < lay_.platforms; ++p) {
    bool reported = forced[p];
    for (const Witness& w : witnesses_)
      if (!w.tick && w.index == p) reported = reported || witnessValue(w, y_.data(), lambda) >= 0;
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
