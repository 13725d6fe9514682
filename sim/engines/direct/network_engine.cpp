#include "sim/engines/direct/network_engine.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include "models/network_equations.h"
#include "sim/engines/direct/direct_engine.h"
#include "sim/events/resolver.h"
#include "sim/events/witness.h"
#include "sim/ode/rk_stepper.h"
#include "sim/ode/rk_tableau.h"
#include "sim/ode/root_find.h"

namespace metrosync {

namespace {

using network::NetworkEquations;

constexpr double kTwoPi = 6.283185307179586;
// The longest step, in fast periods: short enough that a witness cannot cross and return within
// one step for any amplitude the escapement sustains (a tick witness stays above zero for about a
// tenth of a period), long enough to cost nothing when the accuracy sets the step.
constexpr double kMaxStepPeriods = 0.05;
// The shortest step, relative to the run's time: below it the step size has underflowed.
constexpr double kMinStepRelative = 1e-14;
// Points of the dense output scanned for the reversal of a slip that started from rest within
// the step (locate()).
constexpr int kRestScan = 16;
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
  NetworkRunReport run();

 private:
  std::vector<double> witnessValues(const double* y);
  bool armed(const Witness& w) const;
  double witnessValue(const Witness& w, const double* y, const std::vector<double>& lambda) const;
  std::optional<double> locate(const std::vector<double>& g0, const std::vector<double>& g1);
  void resolveWindow(double t_e);
  void settleSupports();
  void absorb(const WindowOutcome& out, int p);
  void emitSamples(double t_limit, bool inclusive);
  void setTolerances(const Rig& rig);
  void fail(double t, const std::string& why);

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
  NetworkRunReport report_;
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
  report_.integrator = tab_.name;
  report_.fast_period_s = period_;
  report_.ticks.assign(net.numMetronomes(), 0);
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
    std::optional<CoulombLaw> law;
    if (b.moves && b.friction.setValued()) {
      law = b.friction.coulomb;
      witnesses_.push_back({false, p, 0});
    }
    resolvers_.emplace_back(esc, law, period_, th0);
    views_.push_back(std::make_unique<ContactView>(eq_, y_, modes_, p, report_.events));
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
  const double g = PlatformWitness::value(b.friction.coulomb, modes_[w.index],
                                          eq_.slipVelocity(y, w.index), lambda[w.index]);
  return risingSign(PlatformWitness::kDirection) * g;
}

bool NetworkRun::armed(const Witness& w) const {
  int p = 0;  // the platform of pendulum w.index: its resolver numbers its pendulums from 0
  while (w.index >= eq_.block(p).first + eq_.block(p).count) ++p;
  return resolvers_[p].armed(w.index - eq_.block(p).first, w.side);
}

std::vector<double> NetworkRun::witnessValues(const double* y) {
  const std::vector<double> lambda = eq_.holdingForces(y, modes_);
  std::vector<double> g(witnesses_.size());
  for (std::size_t i = 0; i < witnesses_.size(); ++i) g[i] = witnessValue(witnesses_[i], y, lambda);
  return g;
}

// The earliest crossing in the attempted step, as a fraction of it (the bracket's upper end:
// every witness evaluated there has crossed); nullopt if none.
std::optional<double> NetworkRun::locate(const std::vector<double>& g0,
                                         const std::vector<double>& g1) {
  std::optional<double> earliest;
  for (std::size_t i = 0; i < witnesses_.size(); ++i) {
    const Witness& w = witnesses_[i];
    if (w.tick && !armed(w)) continue;
    auto f = [&](double th) {
      if (w.tick)  // one component of the dense output: O(1), whatever the network's size
        return TickWitness{w.index, w.side}.value(eq_.escapement(w.index),
                                                  stepper_.component(lay_.theta(w.index), th));
      stepper_.interpolate(th, scratch_.data());
      return witnessValue(w, scratch_.data(), eq_.holdingForces(scratch_.data(), modes_));
    };
    double a = 0.0, ga = g0[i], b = 1.0, gb = g1[i];
    if (!w.tick && g0[i] == 0 && g1[i] > 0) {
      // a slip that started from rest (its witness exactly 0 at the step's start: no crossing)
      // and runs against its mode at the step's end reversed inside the step: its crossing is
      // bracketed on the dense output (within the first 1 / kRestScan of the step: taken there)
      b = 1.0 / kRestScan;
      gb = f(b);
      for (int k = 1; k < kRestScan && !(ga < 0 && gb >= 0); ++k) {
        a = b, ga = gb;
        b = (k + 1.0) / kRestScan;
        gb = k + 1 < kRestScan ? f(b) : g1[i];
      }
      if (!(ga < 0)) {
        if (!earliest || 1.0 / kRestScan < *earliest) earliest = 1.0 / kRestScan;
        continue;
      }
    } else if (!crossed(Direction::Rising, g0[i], g1[i])) {
      continue;
    }
    const ode::Bracket br = ode::illinois(f, a, ga, b, gb);
    if (!earliest || br.hi < *earliest) earliest = br.hi;
  }
  return earliest;
}

void NetworkRun::absorb(const WindowOutcome& out, int p) {
  report_.ledger.escapement_in_J += out.escapement_in;
  report_.ledger.friction_out_J += out.friction_out;
  report_.stick_slip += out.stick_slip;
  report_.slip_reversals += out.slip_reversals;
  for (int j : out.ticked) ++report_.ticks[eq_.pendulum(eq_.block(p).first + j).rig_index];
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
              ? u != 0 || b.friction.coulomb.breaksFree(eq_.holdingForces(y_.data(), modes_)[p])
              : static_cast<int>(modes_[p]) * u <= 0;
      if (!off) continue;
      const WindowOutcome out = resolvers_[p].settleAfterSupportImpulse(*views_[p]);
      absorb(out, p);
      changed = true;
    }
    if (!changed) return;
  }
}

void NetworkRun::resolveWindow(double t_e) {
  const std::vector<double> lambda = eq_.holdingForces(y_.data(), modes_);
  for (int p = 0; p < lay_.platforms; ++p) {
    bool reported = false;
    for (const Witness& w : witnesses_)
      if (!w.tick && w.index == p) reported = witnessValue(w, y_.data(), lambda) >= 0;
    absorb(resolvers_[p].resolve(*views_[p], reported), p);
  }
  settleSupports();
  // a window that follows the last one within the localization's resolution (a few ulps of t: a
  // contact left just past its witness by the last window's impulses, found again at the
  // restart) is that window continued, not a new one (sim/events/window.h: one window per
  // instant)
  if (!(t_e - last_window_t_ <= kSameInstantUlps * std::numeric_limits<double>::epsilon() * t_e))
    ++report_.events;
  last_window_t_ = t_e;
}

void NetworkRun::emitSamples(double t_limit, bool inclusive) {
  const double t0 = stepper_.t(), h = stepper_.h();
  for (;;) {
    const double ts = next_sample_ * sample_dt_;
    if (ts > t_end_ || ts > t_limit || (!inclusive && ts == t_limit)) return;
    stepper_.interpolate(h > 0 ? (ts - t0) / h : 0.0, scratch_.data());
    sink_.sample(ts, scratch_, modes_);
    ++next_sample_;
  }
}

void NetworkRun::fail(double t, const std::string& why) {
  report_.complete = false;
  report_.failure = "at t = " + std::to_string(t) + " s: " + why;
}

NetworkRunReport NetworkRun::run() {
  scratch_.resize(lay_.dim());
  for (int p = 0; p < lay_.platforms; ++p)
    if (eq_.block(p).moves && eq_.block(p).friction.setValued())
      resolvers_[p].settleAtStart(*views_[p]);
  report_.ledger.initial_J = eq_.energy(y_.data());
  sink_.sample(0.0, y_, modes_);
  next_sample_ = 1;
  stepper_.restart(0.0, y_.data());
  const double h_max = kMaxStepPeriods * period_;
  double h = stepper_.initialStepSize(h_max);
  std::vector<double> g0 = witnessValues(y_.data());
  while (stepper_.t() < t_end_) {
    const double t = stepper_.t();
    const double step = std::min({h, h_max, t_end_ - t});
    if (!(step > kMinStepRelative * std::max(1.0, t_end_))) {
      fail(t, "step size underflow");
      return report_;
    }
    const double err = stepper_.attempt(step);
    if (!(err <= 1.0)) {
      if (!std::isfinite(err)) {
        fail(t, "the state is not finite");
        return report_;
      }
      h = stepper_.nextStepSize(step, err, false);
      continue;
    }
    ++report_.steps;
    h = stepper_.nextStepSize(step, err, true);
    const std::vector<double> g1 = witnessValues(stepper_.y1());
    const std::optional<double> th = locate(g0, g1);
    if (!th) {
      emitSamples(stepper_.t1(), true);
      stepper_.advance();
      for (int p = 0; p < lay_.platforms; ++p) resolvers_[p].rearm(*views_[p]);
      std::copy(stepper_.y(), stepper_.y() + lay_.dim(), y_.begin());
      g0 = g1;
      continue;
    }
    const double t_e = t + *th * step;
    emitSamples(t_e, false);
    stepper_.interpolate(*th, y_.data());
    resolveWindow(t_e);
    for (int p = 0; p < lay_.platforms; ++p) resolvers_[p].rearm(*views_[p]);
    stepper_.restart(t_e, y_.data());
    g0 = witnessValues(y_.data());
  }
  emitSamples(t_end_, true);
  report_.rhs_evals = stepper_.evaluations();
  report_.t_end = stepper_.t();
  report_.final_state = y_;
  report_.ledger.final_J = eq_.energy(y_.data());
  report_.ledger.damping_out_J = y_[lay_.dampingWork()] + y_[lay_.damperWork()];
  report_.ledger.friction_out_J += y_[lay_.frictionWork()];
  return report_;
}

}  // namespace

NetworkRunReport runNetworkDirect(const Network& net, NetworkSink& sink) {
  return NetworkRun(net, sink).run();
}

}  // namespace metrosync
