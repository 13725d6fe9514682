// The direct engine's one run (issue 24): a single rig and a network of platforms are the same
// run over a different model. The run owns what is the same for every model -- the step loop
// (sim/engines/direct/step_loop.h), the witness list (sim/events/witness_list.h), the windows'
// location (sim/events/window.h), one shared resolver per platform (sim/events/resolver.h), the
// contact decision at a window's end, the settling of supports, the counts, the ledger's totals
// and the storm rule. The model says what its state is and what its files want:
//
//   using Stepper;  Stepper& stepper();  const RkTableau& tableau() const;
//   const Layout& layout() const;         theta(j), omega(j), v(p), dampingWork(), dim()
//   int platforms() const;  int first(int p) const;  int count(int p) const;
//   bool moves(int p) const;              a platform that is not fixed
//   const PlatformFriction& contact(int p) const;  the law under p (set-valued or not)
//   Escapement escapement(int j) const;
//   PlatformMode mode(int p) const;
//   double slipVelocity(int p, const double* y) const;  its xdot against the platform below
//   double holdingForce(int p, const double* y) const;  the force friction holds while stuck
//   static constexpr bool kHoldingForceRate;  and if true, double holdingForceRate(int p, y)
//   EventSystem& view(int p, double* y, double t);      platform p seen by its resolver, on y
//   int below(int p) const;  int rigIndex(int j) const;  (its metronome's index for the counts)
//   double period() const; double maxStepSize() const; double accuracy() const; double tEnd()
//   const; double energy(const double* y) const;  double dampingOut(const double* y) const;
//   std::vector<double> startState();   int metronomes() const;  (the counts' size)
//   recording: start(y), samplesBefore(stepper, t, inclusive), window(y, t) (before and after
//   one), last(y, t), close(report, y, t); std::string failureText(double t, const std::string&).
//
// The contact decision (as the Simbody engine's, sim/engines/simbody/platform_run.cpp): each
// platform's resolver acts in file order; its contact reports when its witness has crossed -- a
// stuck margin judged on the window's state before any impulse, a slip velocity when the
// platform's turn comes (an earlier platform's tick may have moved the one below it) -- or when
// its slip was stopped where it could not get going. With two or more moving platforms, one's
// impulse can leave another's contact inconsistent: those settle after (settleSupports).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "contact/escapement.h"
#include "sim/engines/direct/direct_options.h"
#include "sim/engines/direct/start_state.h"
#include "sim/engines/direct/step_loop.h"
#include "sim/events/crossing.h"
#include "sim/events/resolver.h"
#include "sim/events/storm_guard.h"
#include "sim/events/window.h"
#include "sim/events/witness.h"
#include "sim/events/witness_list.h"
#include "sim/record/run_report.h"
#include "sim/record/split_timer.h"

namespace metrosync::direct {

// Resolution passes per event window: each pass settles the platforms whose support moved; a
// stack of P platforms needs at most P passes.
constexpr int kSettlePassesPerPlatform = 2;

// Two windows this close (in ulps of t) are one instant: the localization resolves no finer (a
// contact left just past its witness by the last window's impulses, found again at the restart,
// is that window continued: sim/events/window.h, one window per instant).
constexpr double kSameInstantUlps = 16;

template <class Model>
class DirectRun {
 public:
  template <class... Args>
  explicit DirectRun(const DirectOptions& opt, Args&&... args)
      : opt_(opt), m_(timer_, std::forward<Args>(args)...) {}
  RunReport run();

  // --- the hooks of the run loop (sim/engines/direct/step_loop.h) ---------------------------
  auto& stepper() { return m_.stepper(); }
  const double* mechanicalEnd(const double* y) const { return y + m_.layout().dampingWork(); }
  bool complete() const { return report_.complete; }
  void countStep() { ++report_.counts.steps; }
  bool findCrossings();
  void emitSamplesBefore(double t_limit, bool inclusive) {
    m_.samplesBefore(m_.stepper(), t_limit, inclusive);
  }
  void rearm(const double* y) {
    for (int j = 0; j < n_; ++j)
      resolvers_[platform_of_[j]].rearm(j - m_.first(platform_of_[j]), y[m_.layout().theta(j)]);
  }
  double locateWindow();
  void resolveWindow(double t_e, double th_e);
  void fail(double t, const std::string& why) {
    if (!report_.complete) return;
    report_.complete = false;
    report_.failure = m_.failureText(t, why);
  }

  // --- witnesses: the model's side of the shared list (sim/events/witness_list.h) ------------
  bool armed(const RunWitness& w) const {
    const int p = platform_of_[w.index];
    return resolvers_[p].armed(w.index - m_.first(p), w.side);
  }
  std::optional<LinearForm> linearForm(const RunWitness& w) const;
  std::optional<WindowCrossing> detectStuck(int index, const RunWitness& w);
  double stuckValueAt(const RunWitness& w, double th) {
    m_.stepper().interpolate(th, scratch_.data());
    return stuckMargin(w.index, scratch_.data());
  }

 private:
  void setUp(const double* y0);
  // a stuck contact's witness made rising: -stickMargin = |H| - static bound, and its rate
  double stuckMargin(int p, const double* y) const {
    return risingSign(PlatformWitness::kDirection) *
           PlatformWitness::value(m_.contact(p).bounds(), PlatformMode::Stuck, 0.0,
                                  m_.holdingForce(p, y));
  }
  double stuckMarginRate(int p, const double* y) const {
    const double h = m_.holdingForce(p, y);
    return (h >= 0 ? 1.0 : -1.0) * m_.holdingForceRate(p, y);
  }
  bool hasContact(int p) const { return m_.contact(p).setValued(); }
  void decideContacts(double th_e);
  void settleSupports(double t_e);
  void absorb(const WindowOutcome& out, int p);
  void countWindow(double t_e);
  void finish();

  DirectOptions opt_;
  SplitTimer timer_;  // the engine's time against the recording's (the model records with it)
  Model m_;
  int n_ = 0;                     // swinging pendulums
  std::vector<int> platform_of_;  // (n x 1) pendulum j's platform
  std::vector<double> theta_c_;   // (n x 1) escapement angles
  int moving_ = 0;                // platforms that move
  std::vector<EventResolver> resolvers_;
  WitnessList witnesses_;
  std::vector<char> maybe_;     // (n x 1): may pendulum j's tick witnesses report in this step?
  std::vector<char> reported_;  // (P x 1): the contact's witness reported in this window
  std::vector<double> margin_;  // (P x 1): the stuck margins before any impulse
  std::vector<double> ev_, scratch_;  // the window's state; the witnesses' scratch
  RunReport report_;
  double last_window_t_ = -1.0;
  bool debug_ = std::getenv("METROSYNC_DEBUG") != nullptr;
};

// --- witnesses ------------------------------------------------------------------------------

// A tick on its angle, a slipping contact on its slip velocity against the platform below.
template <class Model>
std::optional<LinearForm> DirectRun<Model>::linearForm(const RunWitness& w) const {
  const auto& lay = m_.layout();
  if (w.tick())
    return LinearForm{lay.theta(w.index), -1, static_cast<double>(w.side), theta_c_[w.index]};
  const int p = w.index;
  const PlatformMode mode = m_.mode(p);
  if (mode == PlatformMode::Stuck) return std::nullopt;
  const int below = m_.below(p);
  return LinearForm{lay.v(p), below < 0 ? -1 : lay.v(below),
                    -static_cast<double>(static_cast<int>(mode)), 0.0};
}

// A stuck contact's crossing: its margin's sign change between the step's ends, or a hidden one
// at an extreme of the margin when the model knows the holding force's rate.
template <class Model>
std::optional<WindowCrossing> DirectRun<Model>::detectStuck(int index, const RunWitness& w) {
  auto& s = m_.stepper();
  const int p = w.index;
  auto value_at = [&](double th) { return stuckValueAt(w, th); };
  using Rates = std::optional<std::pair<double, double>>;
  if constexpr (Model::kHoldingForceRate) {
    auto end_rates = [&] { return Rates({stuckMarginRate(p, s.y()), stuckMarginRate(p, s.y1())}); };
    auto rate_at = [&](double th) {
      s.interpolate(th, scratch_.data());
      return stuckMarginRate(p, scratch_.data());
    };
    return detectMargin(index, stuckMargin(p, s.y()), stuckMargin(p, s.y1()), end_rates, value_at,
                        rate_at);
  } else {
    return detectMargin(
        index, stuckMargin(p, s.y()), stuckMargin(p, s.y1()), [] { return Rates(); }, value_at,
        [](double) { return 0.0; });
  }
}

// A pendulum's tick witnesses (side * theta - theta_c) can report only if |theta| ends at or past
// theta_c, or if its rate theta' = thetadot changes sign inside the step (a grazing maximum, or a
// dip before a crossing): detectComponent() reports nothing else (its rates at the step's ends are
// f(y0) and f(y1), whose angle rows are the rates). One pass over the pendulums finds those; with
// N pendulums most steps have none, and the 2N witnesses are not looked at one by one.
// Inlined into the step loop (it runs on every kept step): out of line, the single board's run
// executed 1.4% more instructions (callgrind, peer-n2).
template <class Model>
inline __attribute__((always_inline)) bool DirectRun<Model>::findCrossings() {
  auto& s = m_.stepper();
  const auto& lay = m_.layout();
  const double* w0s = s.y() + lay.omega(0);
  const double* w1s = s.y1() + lay.omega(0);
  const double* th1s = s.y1() + lay.theta(0);
  for (int j = 0; j < n_; ++j) {
    const double w0 = w0s[j], w1 = w1s[j];
    const bool turns = (w0 > 0 && w1 < 0) || (w0 < 0 && w1 > 0);  // not w0 * w1: underflow
    maybe_[j] = std::abs(th1s[j]) >= theta_c_[j] || turns;
  }
  return witnesses_.findCrossings(
      s, *this, [&](const RunWitness& w) { return !w.tick() || maybe_[w.index]; });
}

// The window (sim/events/window.h): every crossing bracketed, the end at the earliest. A
// witness on one component of the state (a tick, a slip on the table) is bracketed on that
// component's interpolant as a polynomial and confirmed on the exact interpolant.
template <class Model>
double DirectRun<Model>::locateWindow() {
  auto& s = m_.stepper();
  using Poly = typename std::decay_t<decltype(s)>::Polynomial;
  struct PolyWitness {  // sign * y_k(th) - offset (a linear form with b < 0)
    Poly p;
    double sign, offset;
    double operator()(double th) const { return sign * p(th) - offset; }
    std::pair<double, double> valueRate(double th) const {
      const auto [v, r] = p.valueRate(th);
      return {sign * v - offset, sign * r};
    }
  };
  auto approx = [&](int w) -> std::optional<PolyWitness> {
    const std::optional<LinearForm> f = linearForm(witnesses_[w]);
    if (!f || f->b >= 0) return std::nullopt;
    return PolyWitness{s.componentPolynomial(f->a), f->sign, f->offset};
  };
  return metrosync::locateWindow(
      witnesses_.found(), [&](int w, double th) { return witnesses_.valueAt(s, *this, w, th); },
      approx);
}

// --- the window -----------------------------------------------------------------------------

// Which contacts report (the rule in the head of this file); the slip velocities are judged at
// each platform's turn, in resolveWindow.
template <class Model>
void DirectRun<Model>::decideContacts(double th_e) {
  std::fill(reported_.begin(), reported_.end(), 0);
  for (const WindowCrossing& c : witnesses_.found())
    if (c.forced && c.th.hi <= th_e) reported_[witnesses_[c.witness].index] = 1;
  for (int p = 0; p < m_.platforms(); ++p)
    if (hasContact(p) && m_.mode(p) == PlatformMode::Stuck) margin_[p] = stuckMargin(p, ev_.data());
}

// The window's end state in ev_, resolved; the escapements re-armed on the result, the stepper
// restarted from it.
template <class Model>
void DirectRun<Model>::resolveWindow(double t_e, double th_e) {
  auto& s = m_.stepper();
  s.interpolate(th_e, ev_.data());
  m_.window(ev_.data(), t_e);  // the last state before the event
  decideContacts(th_e);
  for (int p = 0; p < m_.platforms(); ++p) {
    bool reported = reported_[p];
    if (hasContact(p)) {
      const PlatformMode mode = m_.mode(p);
      const double g = mode == PlatformMode::Stuck
                           ? margin_[p]
                           : risingSign(PlatformWitness::kDirection) *
                                 PlatformWitness::value(m_.contact(p).bounds(), mode,
                                                        m_.slipVelocity(p, ev_.data()), 0.0);
      reported = reported || g >= 0;
    }
    if (debug_)
      std::fprintf(stderr, "event t %.17g th %.17g platform %d reported %d mode %d\n", t_e, th_e, p,
                   static_cast<int>(reported), static_cast<int>(m_.mode(p)));
    absorb(resolvers_[p].resolve(m_.view(p, ev_.data(), t_e), reported), p);
  }
  if (moving_ >= 2) settleSupports(t_e);
  countWindow(t_e);
  rearm(ev_.data());
  s.restart(t_e, ev_.data());
  m_.window(ev_.data(), t_e);  // and the first after it
}

// Platforms whose contact the window's later changes left inconsistent: stuck with a velocity (an
// impulse below them), stuck beyond the bound (another contact's switch or tick changed the
// forces on it after its own rule was applied: left so, its witness would start below zero and
// never cross), or slipping against their mode.
template <class Model>
void DirectRun<Model>::settleSupports(double t_e) {
  for (int pass = 0; pass < kSettlePassesPerPlatform * m_.platforms(); ++pass) {
    bool changed = false;
    for (int p = 0; p < m_.platforms(); ++p) {
      if (!hasContact(p)) continue;
      const double u = m_.slipVelocity(p, ev_.data());
      const PlatformMode mode = m_.mode(p);
      const bool off =
          mode == PlatformMode::Stuck
              ? u != 0 || m_.contact(p).bounds().breaksFree(m_.holdingForce(p, ev_.data()))
              : static_cast<int>(mode) * u <= 0;
      if (!off) continue;
      absorb(resolvers_[p].settleAfterSupportImpulse(m_.view(p, ev_.data(), t_e)), p);
      changed = true;
    }
    if (!changed) return;
  }
}

template <class Model>
void DirectRun<Model>::absorb(const WindowOutcome& out, int p) {
  report_.ledger.escapement_in_J += out.escapement_in;
  report_.ledger.friction_out_J += out.friction_out;
  report_.counts.stick_slip += out.stick_slip;
  report_.counts.slip_reversals += out.slip_reversals;
  for (int j : out.ticked) ++report_.counts.escapements[m_.rigIndex(m_.first(p) + j)];
}

template <class Model>
void DirectRun<Model>::countWindow(double t_e) {
  if (!(t_e - last_window_t_ <= kSameInstantUlps * std::numeric_limits<double>::epsilon() * t_e))
    ++report_.counts.events;
  last_window_t_ = t_e;
}

// --- the run --------------------------------------------------------------------------------

// The witnesses and resolvers of every platform, armed by the start state y0.
template <class Model>
void DirectRun<Model>::setUp(const double* y0) {
  const auto& lay = m_.layout();
  n_ = lay.n;
  platform_of_.assign(n_, 0);
  theta_c_.assign(n_, 0.0);
  maybe_.assign(n_, 0);
  reported_.assign(m_.platforms(), 0);
  margin_.assign(m_.platforms(), 0.0);
  ev_.assign(lay.dim(), 0.0);
  scratch_.assign(lay.dim(), 0.0);
  for (int p = 0; p < m_.platforms(); ++p) {
    for (int j = m_.first(p); j < m_.first(p) + m_.count(p); ++j) {
      platform_of_[j] = p;
      theta_c_[j] = m_.escapement(j).theta_c;
      if (m_.escapement(j).active()) witnesses_.addTicks(j);
    }
    if (hasContact(p)) witnesses_.addContact(p);
    if (m_.moves(p)) ++moving_;
    resolvers_.push_back(startResolver(
        lay, y0, m_.first(p), m_.count(p), [&](int j) { return m_.escapement(j); }, m_.contact(p),
        m_.period()));
  }
}

template <class Model>
RunReport DirectRun<Model>::run() {
  timer_ = SplitTimer();
  report_.model = "full";
  report_.engine = "direct";
  report_.integrator = m_.tableau().name;
  report_.accuracy = m_.accuracy();
  report_.counts.escapements.assign(m_.metronomes(), 0);
  report_.fast_period_s = m_.period();
  std::vector<double> y = m_.startState();
  setUp(y.data());
  for (int p = 0; p < m_.platforms(); ++p)
    if (hasContact(p)) resolvers_[p].settleAtStart(m_.view(p, y.data(), 0.0));
  report_.ledger.initial_J = m_.energy(y.data());
  const double h_max = m_.maxStepSize();
  StormGuard storm(m_.period(), opt_.storm_events, opt_.storm_window);
  auto& s = m_.stepper();
  s.restart(0.0, y.data());
  try {
    m_.start(y.data());
    integrateTo(*this, m_.tEnd(),
                firstStepSize(h_max, m_.period(), m_.accuracy(), m_.tableau().order), h_max,
                m_.period(), storm);
  } catch (const std::exception& e) {
    fail(s.t(), e.what());
  }
  finish();
  return report_;
}

// The run's end: its final state at t_end exactly when complete (the last step ends there), else
// where it stopped; the last samples, the counts and the ledger.
template <class Model>
void DirectRun<Model>::finish() {
  auto& s = m_.stepper();
  const double t_end = m_.tEnd();
  const double t_fin = s.t() >= t_end * (1 - 1e-15) && report_.complete ? t_end : s.t();
  const std::vector<double> y(s.y(), s.y() + m_.layout().dim());
  report_.t_end = t_fin;
  try {
    m_.last(y.data(), t_fin, report_);
  } catch (const std::exception& e) {
    fail(t_fin, e.what());
  }
  try {
    m_.close(report_);
  } catch (const std::exception& e) {
    fail(t_fin, e.what());
  }
  report_.counts.rhs_evals = s.evaluations();
  report_.ledger.final_J = m_.energy(y.data());
  report_.ledger.damping_out_J = m_.dampingOut(y.data());
  report_.ledger.friction_out_J += y[m_.layout().frictionWork()];
  report_.has_ledger = true;
  report_.wall_seconds = timer_.wallSeconds();
  report_.engine_seconds = report_.wall_seconds - timer_.recordingSeconds(report_.wall_seconds);
}

}  // namespace metrosync::direct
