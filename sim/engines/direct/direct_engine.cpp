// The direct engine's run loop. Top to bottom:
//   1. witnesses (sim/events/witness.h), each turned into one that rises through zero at its
//      event: ticks side * theta_i - theta_c,i (only while armed, sim/events/resolver.h); the
//      platform's PlatformWitness with the sign flipped (|H| - bound while stuck, -mode * xdot
//      while slipping), in the list the network's run uses too (sim/events/witness_list.h).
//   2. detection on each kept step (the list's): a sign change between the step's ends, or a
//      hidden double crossing (grazing) found at the extreme of the witness inside the step (the
//      root of its rate on the dense output); then each crossing is bracketed by Illinois on the
//      dense output to a few ulps. The window ends at the earliest bracket's upper end; every
//      witness past zero there belongs to it (its sign decides, not its bracket: near a root the
//      dense output is not monotone at the ulp level).
//   3. the shared resolver (sim/events/resolver.h) acts on the window's end state, through this
//      engine's EventSystem (the state vector and the platform mode).
//   4. recorders: trajectory rows and envelope samples from the dense output on the shared
//      schedule (sim/events/sample_schedule.h), the energy ledger from two quadrature states.
#include "sim/engines/direct/direct_engine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "base/constants.h"
#include "models/minimal_equations.h"
#include "models/scaling.h"
#include "sim/engines/direct/start_state.h"
#include "sim/engines/direct/step_loop.h"
#include "sim/events/crossing.h"
#include "sim/events/resolver.h"
#include "sim/events/sample_schedule.h"
#include "sim/events/storm_guard.h"
#include "sim/events/window.h"
#include "sim/events/witness.h"
#include "sim/events/witness_list.h"
#include "sim/ode/rk_stepper.h"
#include "sim/ode/root_find.h"
#include "sim/record/envelope_recorder.h"
#include "sim/record/split_timer.h"

namespace metrosync {

const std::vector<std::string>& directIntegratorNames() {
  static const std::vector<std::string> names = {"verner76", "dopri5", "verner65"};
  return names;
}

std::string defaultDirectIntegrator(const Rig& rig) {
  return rig.numSwinging() > 8 ? "dopri5" : "verner76";
}

namespace direct {
namespace {

// The right-hand side in the platform's current mode, with N swinging pendulums known to the
// compiler (or kAnyN): the stepper inlines it into every stage.
template <int N>
class Dynamics final {
 public:
  explicit Dynamics(const MetronomeEquations& eq) : eq_(eq) {}
  void eval(const double* y, double* dy) { eq_.rhsN<N>(y, mode, dy); }
  PlatformMode mode = PlatformMode::Stuck;

 private:
  const MetronomeEquations& eq_;
};

// The state's size for N swinging pendulums: x, xdot, N angles and rates, two ledger quadratures.
constexpr int stateDim(int n) {
  return n > 0 ? 4 + 2 * n : ode::kDynamic;
}

// A crossing found in the current step (sim/events/window.h); `forced` marks a slip that could
// not get going: stopped a sixteenth into the step.
using Crossing = WindowCrossing;

// The run: a stepper, the witnesses, and the shared resolver acting on the event state through
// this class's EventSystem side (the state vector ev_y_ and the platform mode).
template <int N>
class DirectRun : public EventSystem {
 public:
  DirectRun(const Rig& rig, RunSink& sink, const DirectOptions& opt);
  RunReport run();

  // --- EventSystem (on ev_y_) -------------------------------------------------------------
  double theta(int j) const override { return ev_y_[lay_.theta(j)]; }
  double thetadot(int j) const override { return ev_y_[lay_.omega(j)]; }
  double xdot() const override { return ev_y_[StateLayout::kV]; }
  PlatformMode mode() const override { return dyn_.mode; }
  void setMode(PlatformMode m) override {
    dyn_.mode = m;
    if (m == PlatformMode::Stuck) ev_y_[StateLayout::kV] = 0.0;  // held: the residual of a stop
  }
  double holdingForce() override { return eq_.holdingForce(ev_y_); }
  double applyImpulse(const std::vector<double>& pin, double platform) override {
    return eq_.applyImpulse(ev_y_, pin.data(), platform);
  }
  // the angles do not change while a window is resolved: one evaluation per window
  double platformMobility() override {
    if (!(mobility_ > 0)) mobility_ = eq_.platformMobility(ev_y_);
    return mobility_;
  }
  void eventRow(const char* kind) override {
    if (!event_rows_) return;
    RecordingScope rec(timer_);
    sink_.eventRow(kind, makeRow(ev_y_, ev_t_));
  }
  void snapshotBefore() override {
    if (!event_records_) return;
    RecordingScope rec(timer_);
    before_ = makeRow(ev_y_, ev_t_);
  }
  void recordEvent(const char* kind, int j) override {
    if (!event_records_) return;
    RecordingScope rec(timer_);
    sink_.eventRecord(kind, j < 0 ? -1 : eq_.pendulum(j).rig_index, before_, makeRow(ev_y_, ev_t_));
  }

  // --- the run's stages: the hooks of the run loop (sim/engines/direct/step_loop.h) ----------
  std::vector<double> startState();
  double maxStepSize() const;
  auto& stepper() { return stepper_; }
  const double* mechanicalEnd(const double* y) const { return y + lay_.mechanical(); }
  bool complete() const { return report_.complete; }
  void countStep() { ++report_.counts.steps; }
  bool findCrossings();
  double locateWindow();  // brackets the crossings; the window's end th_e
  void resolveWindow(double t_e, double th_e);
  void rearm(const double* y);
  void emitSamplesBefore(double t_limit, bool inclusive);
  void fail(double t, const std::string& why) {
    if (report_.complete) {
      report_.complete = false;
      std::ostringstream os;
      os << "simulation failed at t = " << t << " s (tau = " << sp_.epsilon * omega0_ * t
         << "): " << why;
      report_.failure = os.str();
    }
  }

  // --- witnesses: the model's side of the shared list (sim/events/witness_list.h) ------------
  bool armed(const RunWitness& w) const { return resolver_->armed(w.index, w.side); }
  std::optional<LinearForm> linearForm(const RunWitness& w) const {
    if (w.tick())
      return LinearForm{lay_.theta(w.index), -1, static_cast<double>(w.side),
                        eq_.pendulum(w.index).theta_c};
    if (mode() == PlatformMode::Stuck) return std::nullopt;
    return LinearForm{StateLayout::kV, -1, -static_cast<double>(static_cast<int>(mode())), 0.0};
  }
  std::optional<Crossing> detectStuck(int index, const RunWitness& w);
  double stuckValueAt(const RunWitness&, double th) {
    stepper_.interpolate(th, yb_.data());
    return excessPush(yb_.data());
  }

 private:
  double witnessAt(int w, double th) { return witnesses_.valueAt(stepper_, *this, w, th); }
  // the stuck platform's witness made rising: -stickMargin = |H| - static bound, and its rate
  double excessPush(const double* y) const {
    return risingSign(PlatformWitness::kDirection) *
           PlatformWitness::value(eq_.dryFriction(), PlatformMode::Stuck, 0.0, eq_.holdingForce(y));
  }
  double excessPushRate(const double* y) const {
    const double h = eq_.holdingForce(y);
    return (h >= 0 ? 1.0 : -1.0) * eq_.holdingForceRate(y);
  }

  // --- recording --------------------------------------------------------------------------
  const std::vector<double>& makeRow(const double* y, double t);  // in row_
  void recordTrajectory(const double* y, double t);
  void recordEnvelope(const double* y, double t);

  const Rig& rig_;
  DirectOptions opt_;
  ScaledParams sp_;
  MetronomeEquations eq_;
  StateLayout lay_;
  RunSink& sink_;
  // what the sink takes (asked once): event rows, event records, trajectory rows, envelope rows
  bool event_rows_, event_records_, want_rows_, want_envelope_;
  SplitTimer timer_;  // the engine's time against the recording's
  int n_rig_;
  EnvelopeRecorder env_;
  Dynamics<N> dyn_;
  const RkTableau& tab_;
  // the ledger's two quadratures (the damping's and friction's work) are not in the stages
  ode::RkStepperT<Dynamics<N>, stateDim(N), 2> stepper_;
  RunReport report_;
  double omega0_ = 1.0, period_ = 1.0;
  WitnessList witnesses_;
  std::vector<char> maybe_;  // (n x 1): may pendulum j's tick witnesses report in this step?
  std::optional<EventResolver> resolver_;
  std::optional<SampleSchedule> schedule_;
  double* ev_y_ = nullptr;      // the state the resolver acts on, at time ev_t_
  std::vector<double> before_;  // the state before the event being recorded (events.csv)
  double ev_t_ = 0.0;
  double mobility_ = 0.0;        // platformMobility() at ev_y_'s angles (0: not computed yet)
  std::vector<double> ya_, yb_;  // scratch states (dim): the event's, the witnesses'
  std::vector<double> env_th_, env_w_;
  std::vector<double> row_;         // the trajectory row being written
  double friction_settle_J_ = 0.0;  // kinetic energy removed by plastic stops
  bool debug_ = std::getenv("METROSYNC_DEBUG") != nullptr;
  double t_end_ = 0.0;
};

template <int N>
DirectRun<N>::DirectRun(const Rig& rig, RunSink& sink, const DirectOptions& opt)
    : rig_(rig),
      opt_(opt),
      sp_(computeScaled(rig)),
      eq_(rig),
      lay_(eq_.layout()),
      sink_(sink),
      event_rows_(sink.wantsEventRows()),
      event_records_(sink.wantsEventRecords()),
      want_rows_(sink.wantsTrajectory()),
      want_envelope_(sink.wantsEnvelope()),
      n_rig_(static_cast<int>(rig.metronomes.size())),
      env_(
          sp_.epsilon,
          [&] {
            std::vector<bool> a;
            for (const auto& m : rig.metronomes) a.push_back(!m.locked);
            return a;
          }(),
          sink),
      dyn_(eq_),
      tab_(rkTableau(rig.sim.integrator.empty() ? defaultDirectIntegrator(rig)
                                                : rig.sim.integrator)),
      stepper_(tab_, lay_.dim(), dyn_) {
  report_.model = "full";
  report_.engine = "direct";
  report_.integrator = tab_.name;
  report_.accuracy = rig.sim.accuracy;
  report_.counts.escapements.assign(n_rig_, 0);
  omega0_ = 1.0 / sp_.time_scale_s;
  period_ = kTwoPi / omega0_;
  for (int j = 0; j < lay_.n; ++j)
    if (eq_.escapement(j).active()) witnesses_.addTicks(j);
  if (eq_.friction().setValued()) witnesses_.addContact(0);
  ya_.resize(lay_.dim());
  yb_.resize(lay_.dim());
  env_th_.resize(n_rig_, 0.0);
  env_w_.resize(n_rig_, 0.0);

  stepper_.setTolerances(rig.sim.accuracy, scaledTolerances(rig.sim.accuracy, sp_, lay_));
}

// --- witnesses ------------------------------------------------------------------------------

// |H| - bound while stuck: H is a function of the whole state, its rate known in closed form.
template <int N>
std::optional<Crossing> DirectRun<N>::detectStuck(int index, const RunWitness&) {
  auto end_rates = [&] {
    return std::optional<std::pair<double, double>>(
        {excessPushRate(stepper_.y()), excessPushRate(stepper_.y1())});
  };
  auto value_at = [&](double th) { return stuckValueAt(RunWitness{}, th); };
  auto rate_at = [&](double th) {
    stepper_.interpolate(th, yb_.data());
    return excessPushRate(yb_.data());
  };
  return metrosync::detectMargin(index, excessPush(stepper_.y()), excessPush(stepper_.y1()),
                                 end_rates, value_at, rate_at);
}

// --- recording ------------------------------------------------------------------------------

template <int N>
const std::vector<double>& DirectRun<N>::makeRow(const double* y, double t) {
  std::vector<double>& row = row_;
  row.clear();
  const bool scaled = rig_.units == Units::Scaled;
  const double xs = scaled ? 1.0 / sp_.x_scale_m : 1.0;
  const double as = scaled ? 1.0 / sp_.angle_scale : 1.0;
  const double ts = scaled ? omega0_ : 1.0;
  row.push_back(t * ts);
  row.push_back(y[StateLayout::kX] * xs);
  row.push_back(y[StateLayout::kV] * xs / ts);
  int j = 0;
  for (int i = 0; i < n_rig_; ++i) {
    if (rig_.metronomes[i].locked) {
      row.push_back(0.0);
      row.push_back(0.0);
      continue;
    }
    row.push_back(y[lay_.theta(j)] * as);
    row.push_back(y[lay_.omega(j)] * as / ts);
    ++j;
  }
  if (eq_.friction().setValued()) {
    row.push_back(static_cast<int>(mode()));
  } else {
    const double v = y[StateLayout::kV];
    row.push_back(v > 0 ? 1 : (v < 0 ? -1 : 0));
  }
  return row;
}

template <int N>
void DirectRun<N>::recordTrajectory(const double* y, double t) {
  if (!want_rows_) return;
  RecordingScope rec(timer_);
  sink_.trajectoryRow(makeRow(y, t));
}

template <int N>
void DirectRun<N>::recordEnvelope(const double* y, double t) {
  if (!want_envelope_) return;
  RecordingScope rec(timer_);
  const double* th = y + lay_.theta(0);
  const double* w = y + lay_.omega(0);
  const double w_scale = sp_.angle_scale * omega0_;
  if (lay_.n == n_rig_) {  // no locked metronome: the angles and rates in rig order
    for (int i = 0; i < n_rig_; ++i) env_th_[i] = th[i] / sp_.angle_scale;
    for (int i = 0; i < n_rig_; ++i) env_w_[i] = w[i] / w_scale;
  } else {
    for (int j = 0; j < lay_.n; ++j) {
      const int i = eq_.pendulum(j).rig_index;
      env_th_[i] = th[j] / sp_.angle_scale;
      env_w_[i] = w[j] / w_scale;
    }
  }
  env_.sample(t * omega0_, env_th_.data(), env_w_.data());
}

// Samples due in the current step before t_limit (or at it, if inclusive), from the dense output.
template <int N>
void DirectRun<N>::emitSamplesBefore(double t_limit, bool inclusive) {
  const double t_next = schedule_->next();
  if (!(t_next < t_limit || (inclusive && t_next == t_limit))) return;
  RecordingScope rec(timer_);
  const double t0 = stepper_.t(), h = stepper_.h();
  schedule_->takeDue(t_limit, inclusive, [&](double ts, bool row, bool env) {
    const double th = std::clamp((ts - t0) / h, 0.0, 1.0);
    // an envelope sample needs the angles and rates only (2N of the 2N + 4 components)
    if (row)
      stepper_.interpolate(th, ya_.data());
    else
      stepper_.interpolateRange(th, lay_.theta(0), 2 * lay_.n, ya_.data());
    if (row) recordTrajectory(ya_.data(), ts);
    if (env) recordEnvelope(ya_.data(), ts);
  });
}

// --- the run's stages -----------------------------------------------------------------------

// The rig's start state; the resolver, armed by it; the platform's mode decided at rest.
template <int N>
std::vector<double> DirectRun<N>::startState() {
  std::vector<double> y(lay_.dim(), 0.0);
  writePlatformStart(rig_, eq_.hasPlatform(), lay_, 0, 0, y.data());
  resolver_.emplace(startResolver(
      lay_, y.data(), 0, lay_.n, [&](int j) { return eq_.escapement(j); }, eq_.friction(),
      period_));
  if (eq_.friction().setValued()) {
    ev_y_ = y.data();
    mobility_ = 0.0;
    ev_t_ = 0.0;
    resolver_->settleAtStart(*this);
  }
  return y;
}

// The largest step: a fraction of the fastest oscillation (pendulums, platform spring), so that a
// step holds at most one extreme of any witness.
template <int N>
double DirectRun<N>::maxStepSize() const {
  double fastest = period_;
  for (int j = 0; j < lay_.n; ++j) {
    const PendulumConstants& p = eq_.pendulum(j);
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

// A pendulum's tick witnesses (side * theta - theta_c) can report only if |theta| ends at or past
// theta_c, or if its rate theta' = thetadot changes sign inside the step (a grazing maximum, or a
// dip before a crossing): detectComponent() reports nothing else (its rates at the step's ends are
// f(y0) and f(y1), whose angle rows are the rates). One pass over the pendulums finds those; with
// N pendulums most steps have none, and the 2N witnesses are not looked at one by one.
template <int N>
bool DirectRun<N>::findCrossings() {
  const double* y0 = stepper_.y();
  const double* y1 = stepper_.y1();
  const int n = lay_.n;
  maybe_.resize(n);
  for (int j = 0; j < n; ++j) {
    const double th1 = y1[lay_.theta(j)];
    const double w0 = y0[lay_.omega(j)], w1 = y1[lay_.omega(j)];
    const bool turns = (w0 > 0 && w1 < 0) || (w0 < 0 && w1 > 0);  // not w0 * w1: underflow
    maybe_[j] = std::abs(th1) >= eq_.pendulum(j).theta_c || turns;
  }
  return witnesses_.findCrossings(
      stepper_, *this, [&](const RunWitness& w) { return !w.tick() || maybe_[w.index]; });
}

// The window (sim/events/window.h): every crossing bracketed, the end at the earliest.
template <int N>
double DirectRun<N>::locateWindow() {
  // a tick's witness and a slip's are one component of the state: bracketed on that component's
  // interpolant as a polynomial, confirmed on the exact interpolant; a stuck platform's margin
  // is a function of the whole state
  using Poly = typename decltype(stepper_)::Polynomial;
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
    if (!f) return std::nullopt;
    return PolyWitness{stepper_.componentPolynomial(f->a), f->sign, f->offset};
  };
  return metrosync::locateWindow(
      witnesses_.found(), [&](int w, double th) { return witnessAt(w, th); }, approx);
}

// The window's end state in ya_: the platform's witness decides whether it switches (a tick
// witness needs no report: the resolver takes every due tick from the state), the resolver acts,
// the stepper restarts from the result.
template <int N>
void DirectRun<N>::resolveWindow(double t_e, double th_e) {
  stepper_.interpolate(th_e, ya_.data());
  bool platform = false;
  for (const Crossing& c : witnesses_.found())
    if (!witnesses_[c.witness].tick() && (c.forced || witnessAt(c.witness, th_e) >= 0))
      platform = true;
  ++report_.counts.events;
  if (debug_)
    std::fprintf(stderr, "event t %.17g th %.17g platform %d mode %d v %.6g\n", t_e, th_e,
                 static_cast<int>(platform), static_cast<int>(mode()), ya_[StateLayout::kV]);
  recordEnvelope(ya_.data(), t_e);  // the last state before the event
  ev_y_ = ya_.data();
  ev_t_ = t_e;
  mobility_ = 0.0;
  const WindowOutcome out = resolver_->resolve(*this, platform);
  for (int j : out.ticked) ++report_.counts.escapements[eq_.pendulum(j).rig_index];
  report_.counts.stick_slip += out.stick_slip;
  report_.counts.slip_reversals += out.slip_reversals;
  report_.ledger.escapement_in_J += out.escapement_in;
  friction_settle_J_ += out.friction_out;
  stepper_.restart(t_e, ya_.data());
  recordEnvelope(ya_.data(), t_e);  // and the first after it
}

template <int N>
void DirectRun<N>::rearm(const double* y) {
  for (int j = 0; j < lay_.n; ++j) resolver_->rearm(j, y[lay_.theta(j)]);
}

// --- the run --------------------------------------------------------------------------------

template <int N>
RunReport DirectRun<N>::run() {
  timer_ = SplitTimer();
  t_end_ = rig_.sim.t_end_s;
  schedule_.emplace(rig_.sim.sample_s, period_, t_end_, want_rows_, want_envelope_);
  std::vector<double> y = startState();
  report_.ledger.initial_J = eq_.energy(y.data());
  const double h_max = maxStepSize();
  StormGuard storm(period_, opt_.storm_events, opt_.storm_window);

  stepper_.restart(0.0, y.data());
  double t_fin = 0.0;
  std::vector<double> y_fin = y;
  try {
    recordTrajectory(y.data(), 0.0);
    recordEnvelope(y.data(), 0.0);
    integrateTo(*this, t_end_, firstStepSize(h_max, period_, rig_.sim.accuracy, tab_.order), h_max,
                period_, storm);
    t_fin = stepper_.t() >= t_end_ * (1 - 1e-15) && report_.complete ? t_end_ : stepper_.t();
    std::copy(stepper_.y(), stepper_.y() + lay_.dim(), y_fin.begin());
  } catch (const std::exception& e) {
    fail(stepper_.t(), e.what());
    t_fin = stepper_.t();
    std::copy(stepper_.y(), stepper_.y() + lay_.dim(), y_fin.begin());
  }

  // the end of the run: last trajectory row and the period it closes
  report_.final_trajectory_row = makeRow(y_fin.data(), t_fin);
  try {
    recordTrajectory(y_fin.data(), t_fin);
    recordEnvelope(y_fin.data(), t_fin);
  } catch (const std::exception& e) {
    fail(t_fin, e.what());
  }
  report_.final_row = env_.finish();  // the last period ending at t_fin (SPEC 3 final)

  report_.counts.rhs_evals = stepper_.evaluations();
  report_.ledger.final_J = eq_.energy(y_fin.data());
  report_.ledger.damping_out_J = y_fin[lay_.dampingWork()];
  report_.ledger.friction_out_J = y_fin[lay_.frictionWork()] + friction_settle_J_;
  report_.has_ledger = true;
  report_.wall_seconds = timer_.wallSeconds();
  report_.engine_seconds = report_.wall_seconds - timer_.recordingSeconds(report_.wall_seconds);
  return report_;
}

}  // namespace
}  // namespace direct

RunReport runDirectModel(const Rig& rig, RunSink& sink, const DirectOptions& options) {
  const auto& names = directIntegratorNames();
  if (!rig.sim.integrator.empty() &&
      std::find(names.begin(), names.end(), rig.sim.integrator) == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw std::invalid_argument("simulation.integrator = " + rig.sim.integrator +
                                ": not an integrator of the direct engine (one of: " + list + ")");
  }
  // the state's size known to the compiler for up to kMaxFixedN swinging pendulums (every loop
  // over the state unrolled, every buffer in the run object), dynamic above: the same bits
  const int n = direct::MetronomeEquations(rig).numSwinging();
  switch (n) {
    case 1:
      return direct::DirectRun<1>(rig, sink, options).run();
    case 2:
      return direct::DirectRun<2>(rig, sink, options).run();
    case 3:
      return direct::DirectRun<3>(rig, sink, options).run();
    case 4:
      return direct::DirectRun<4>(rig, sink, options).run();
    case 5:
      return direct::DirectRun<5>(rig, sink, options).run();
    case 6:
      return direct::DirectRun<6>(rig, sink, options).run();
    case 7:
      return direct::DirectRun<7>(rig, sink, options).run();
    case 8:
      return direct::DirectRun<8>(rig, sink, options).run();
    default:
      return direct::DirectRun<direct::MetronomeEquations::kAnyN>(rig, sink, options).run();
  }
}

}  // namespace metrosync
