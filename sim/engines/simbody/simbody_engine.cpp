// The full model's run loop on Simbody. The pieces, top to bottom:
//   1. witnesses (sim/events/witness.h, directions from their types): thin
//      TriggeredEventHandlers that only say "my witness crossed" (ticks: rising side * theta_i -
//      theta_c; platform: falling mode*xdot while slipping, falling stick margin while stuck).
//      Simbody calls every handler whose witness crossed in the localization window, in
//      registration order, on the same state; so none of them acts.
//   2. the shared resolver (sim/events/resolver.h) acts on the whole window at once, through this
//      engine's EventSystem: every due tick as one combined impulse through the unlocked mass
//      matrix, then the platform's Coulomb rule on the resulting state. The result does not
//      depend on the order in which Simbody called the handlers. A window whose only reports are
//      consumed ticks (applied inside their slack) is not an event.
//   3. a grazing guard: a step whose end points both lie inside +-theta_c (or both on one side of
//      xdot = 0) can still have crossed twice; the cubic Hermite through the step's end values
//      finds such steps and the step is redone with smaller steps.
//   4. recorders: trajectory rows and envelope samples by interpolation on the shared schedule
//      (sim/events/sample_schedule.h: the integrator is never forced to stop at a sample), with
//      samples on both sides of every event; the shared storm rule (sim/events/storm_guard.h).
#include "sim/engines/simbody/simbody_engine.h"

#include <Simbody.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <sstream>

#include "models/simbody/metronome_system.h"
#include "sim/engines/simbody/integrators.h"
#include "sim/events/resolver.h"
#include "sim/events/sample_schedule.h"
#include "sim/events/storm_guard.h"
#include "sim/events/witness.h"
#include "sim/record/envelope_recorder.h"
#include "sim/record/split_timer.h"

namespace metrosync {

using namespace SimTK;

// simbodyIntegratorNames(): integrator_names.cpp

namespace {

// What the witnesses report within one localization window: which (pendulum, side) tick
// witnesses and whether the platform's witness crossed. The resolver acts on the state; a report
// only says whether the window is live (a disarmed tick witness crossing, after a tick applied
// inside its slack, changes nothing and is not an event).
struct Pending {
  std::vector<std::pair<int, int>> ticks;
  bool platform = false;
  void clear() {
    ticks.clear();
    platform = false;
  }
};

void setDirection(TriggeredEventHandler& h, Direction d) {
  h.getTriggerInfo().setTriggerOnRisingSignTransition(d != Direction::Falling);
  h.getTriggerInfo().setTriggerOnFallingSignTransition(d != Direction::Rising);
}

class TickHandler : public TriggeredEventHandler {
 public:
  TickHandler(const MetronomeSystem& ms, int i, int side, Pending& pending)
      : TriggeredEventHandler(Stage::Position), ms_(ms), w_{i, side}, pending_(pending) {
    setDirection(*this, TickWitness::kDirection);
    esc_.theta_c = ms.rig().metronomes[i].theta_c_rad;
    esc_.impulse = ms.rig().metronomes[i].impulse_Nms;
  }
  Real getValue(const State& s) const override { return w_.value(esc_, ms_.theta(s, w_.pendulum)); }
  void handleEvent(State&, Real, bool&) const override {
    pending_.ticks.emplace_back(w_.pendulum, w_.side);
  }

 private:
  const MetronomeSystem& ms_;
  TickWitness w_;
  Escapement esc_;
  Pending& pending_;
};

class PlatformHandler : public TriggeredEventHandler {
 public:
  PlatformHandler(const MetronomeSystem& ms, Pending& pending)
      : TriggeredEventHandler(Stage::Acceleration), ms_(ms), pending_(pending) {
    setDirection(*this, PlatformWitness::kDirection);
  }
  // the element's witness is PlatformWitness::value (stick margin / mode * xdot)
  Real getValue(const State& s) const override { return ms_.coulomb()->witness(s); }
  void handleEvent(State&, Real, bool&) const override { pending_.platform = true; }

 private:
  const MetronomeSystem& ms_;
  Pending& pending_;
};

bool allFinite(const Vector& y) {
  for (int k = 0; k < y.size(); ++k)
    if (!std::isfinite(y[k])) return false;
  return true;
}

// Cubic Hermite on [0, h] through (p0, d0), (p1, d1): its extreme value strictly inside the
// step (the largest interior maximum for want_max, else the smallest interior minimum), or NaN
// when it has none there.
double hermiteInteriorExtreme(double p0, double d0, double p1, double d1, double h, bool want_max) {
  const double a = 6 * p0 + 3 * h * d0 - 6 * p1 + 3 * h * d1;
  const double b = -6 * p0 - 4 * h * d0 + 6 * p1 - 2 * h * d1;
  const double c = h * d0;
  auto eval = [&](double s) {
    const double s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * h * d0 + (-2 * s3 + 3 * s2) * p1 +
           (s3 - s2) * h * d1;
  };
  double best = std::nan("");
  auto consider = [&](double s) {
    if (!(s > 0 && s < 1)) return;
    const double v = eval(s);
    if (std::isnan(best) || (want_max ? v > best : v < best)) best = v;
  };
  if (std::abs(a) < 1e-300) {
    if (std::abs(b) > 1e-300) consider(-c / b);
  } else {
    const double disc = b * b - 4 * a * c;
    if (disc >= 0) {
      const double r = std::sqrt(disc);
      consider((-b + r) / (2 * a));
      consider((-b - r) / (2 * a));
    }
  }
  return best;
}

// The run: Simbody's integrator, thin witnesses, and the shared resolver acting on the event
// state through this class's EventSystem side (the State ev_s_).
class FullModelRun : public EventSystem {
 public:
  FullModelRun(const Rig& rig, RunSink& sink)
      : rig_(rig),
        sp_(computeScaled(rig)),
        ms_(rig),
        sink_(sink),
        n_(ms_.numMetronomes()),
        env_(sp_.epsilon, activeMask(rig), sink) {
    report_.model = "full";
    report_.engine = "simbody";
    report_.integrator =
        rig.sim.integrator.empty() ? simbodyIntegratorNames().front() : rig.sim.integrator;
    report_.accuracy = rig.sim.accuracy;
    report_.counts.escapements.assign(n_, 0);
    omega0_ = 1.0 / sp_.time_scale_s;
    period_ = 2 * Pi / omega0_;
    // witnesses: only what the scene needs
    for (int i = 0; i < n_; ++i) {
      if (!ms_.swings(i) || !(rig.metronomes[i].impulse_Nms > 0)) continue;
      ms_.system().addEventHandler(new TickHandler(ms_, i, +1, pending_));
      ms_.system().addEventHandler(new TickHandler(ms_, i, -1, pending_));
    }
    if (ms_.coulomb()) ms_.system().addEventHandler(new PlatformHandler(ms_, pending_));
    ms_.system().setDefaultTimeScale(sp_.time_scale_s);
    ms_.system().realizeTopology();
  }

  RunReport run();

  // --- EventSystem (on ev_s_) -------------------------------------------------------------
  double theta(int i) const override { return ms_.theta(*ev_s_, i); }
  double thetadot(int i) const override { return ms_.thetadot(*ev_s_, i); }
  double xdot() const override { return ms_.xdot(*ev_s_); }
  PlatformMode mode() const override { return ms_.coulomb()->mode(*ev_s_); }
  void setMode(PlatformMode m) override;
  double holdingForce() override {
    ms_.system().realize(*ev_s_, Stage::Acceleration);
    return ms_.coulomb()->holdingForce(*ev_s_);
  }
  double applyImpulse(const std::vector<double>& pin, double platform) override;
  double platformMobility() override;
  void eventRow(const char* kind) override { eventRow(kind, *ev_s_); }
  void snapshotBefore() override {
    if (!sink_.wantsEventRecords()) return;
    RecordingScope rec(timer_);
    before_ = makeRow(*ev_s_, ev_s_->getTime());
  }
  void recordEvent(const char* kind, int i) override {
    if (!sink_.wantsEventRecords()) return;
    RecordingScope rec(timer_);
    sink_.eventRecord(kind, i, before_, makeRow(*ev_s_, ev_s_->getTime()));
  }

 private:
  static std::vector<bool> activeMask(const Rig& rig) {
    std::vector<bool> a;
    for (const auto& m : rig.metronomes) a.push_back(!m.locked);
    return a;
  }

  // --- the run's stages ---------------------------------------------------------------------
  State startState();
  std::unique_ptr<Integrator> makeRunIntegrator(const State& s0);
  // Checks a step just taken: grazing (redo it smaller), a slip that ended inside it (stop).
  // Returns true when the step was redone.
  bool checkNewStep(Integrator& integ, Integrator::SuccessfulStepStatus status);
  void redoStep(Integrator& integ);
  void handleTrigger(Integrator& integ);
  bool windowIsLive() const;
  Stage resolveWindow(State& s);  // the resolver on s; the lowest stage it changed
  void takeSamples(const Integrator& integ, double t_limit);

  // --- recording --------------------------------------------------------------------------
  void recordTrajectory(const State& s, double t);
  std::vector<double> makeRow(const State& s, double t) const;
  void eventRow(const char* kind, const State& s);
  void recordEnvelope(const State& s, double t);
  double energy(const State& s) {
    ms_.system().realize(s, Stage::Velocity);
    return ms_.system().calcEnergy(s);
  }
  int platformColumn(const State& s) const {
    if (ms_.coulomb()) return static_cast<int>(ms_.coulomb()->mode(s));
    const double v = ms_.xdot(s);
    return v > 0 ? 1 : (v < 0 ? -1 : 0);
  }

  // --- grazing guard ----------------------------------------------------------------------
  struct StepEnd {
    double t = 0;
    Vector y;
    std::vector<double> th, w;  // pendulum angle and rate
    double v = 0, a = 0;        // platform velocity and acceleration
  };
  void captureStepEnd(const State& s, StepEnd& e);
  bool grazingMissed(const StepEnd& a, const StepEnd& b, PlatformMode mode, bool event_step) const;

  void fail(double t, const std::string& why) {
    if (report_.complete) {
      report_.complete = false;
      std::ostringstream os;
      // t in the rig's own time unit (seconds, or scaled time for a scaled rig)
      os << "simulation failed at t = " << (rig_.units == Units::Scaled ? t * omega0_ : t)
         << (rig_.units == Units::Scaled ? "" : " s") << " (tau = " << sp_.epsilon * omega0_ * t
         << "): " << why;
      report_.failure = os.str();
    }
  }
  void noteDiscontinuity(double t) {
    if (storm_->note(t)) fail(t, storm_->why());
  }

  const Rig& rig_;
  ScaledParams sp_;
  MetronomeSystem ms_;
  RunSink& sink_;
  SplitTimer timer_;  // the engine's time against the recording's
  int n_;
  EnvelopeRecorder env_;
  Pending pending_;
  RunReport report_;
  double omega0_ = 1;
  double period_ = 1;  // fast period, seconds
  std::optional<EventResolver> resolver_;
  std::optional<SampleSchedule> schedule_;
  std::optional<StormGuard> storm_;
  State* ev_s_ = nullptr;       // the state the resolver acts on
  std::vector<double> before_;  // the state before the event being recorded (events.csv)
  // grazing guard: the last checked step end, and the state of a redo
  StepEnd prev_, cur_;
  double checked_until_ = 0.0;
  double guard_until_ = -1;  // while redoing a grazing step: time until which hmax is reduced
  int guard_depth_ = 0;
  long steps_base_ = 0, evals_base_ = 0, rewinds_ = 0;
  bool debug_ = std::getenv("METROSYNC_DEBUG") != nullptr;
  std::vector<double> scratch_th_, scratch_w_;
};

// --- EventSystem ------------------------------------------------------------------------------

void FullModelRun::setMode(PlatformMode m) {
  const CoulombElement& c = *ms_.coulomb();
  if (m == PlatformMode::Stuck)
    c.stick(*ev_s_);  // the slider locked at xdot = 0: the residual of a stop
  else
    c.slip(*ev_s_, m);
  ms_.system().realize(*ev_s_, Stage::Velocity);
}

double FullModelRun::applyImpulse(const std::vector<double>& pin, double platform) {
  State& s = *ev_s_;
  const CoulombElement* c = ms_.coulomb();
  if (c && c->mode(s) == PlatformMode::Stuck) {
    c->slip(s, PlatformMode::SlipPositive);  // provisional: the resolver sets the mode next
    ms_.system().realize(s, Stage::Position);
  }
  const double e0 = energy(s);
  Vector f(s.getNU(), 0.0), du;
  for (int i = 0; i < n_; ++i)
    if (pin[i] != 0) ms_.pin(i).applyOneMobilityForce(s, 0, pin[i], f);
  if (platform != 0 && ms_.hasPlatform()) ms_.slider().applyOneMobilityForce(s, 0, platform, f);
  ms_.matter().multiplyByMInv(s, f, du);
  s.updU() += du;
  ms_.system().realize(s, Stage::Velocity);
  // the work of the impulse: the kinetic energy jump (the potential energy does not jump)
  return energy(s) - e0;
}

double FullModelRun::platformMobility() {
  const State& s = *ev_s_;
  Vector f(s.getNU(), 0.0), du;
  ms_.slider().applyOneMobilityForce(s, 0, 1.0, f);
  ms_.matter().multiplyByMInv(s, f, du);
  return ms_.slider().getOneFromUPartition(s, 0, du);
}

// --- the run's stages -------------------------------------------------------------------------

// The rig's start state, the resolver armed by it, the platform's mode decided at rest.
State FullModelRun::startState() {
  State s0 = ms_.initialState();
  std::vector<Escapement> esc;
  std::vector<double> theta0;
  for (int i = 0; i < n_; ++i) {
    const MetronomeSpec& m = rig_.metronomes[i];
    esc.push_back({m.theta_c_rad, ms_.swings(i) ? m.impulse_Nms : 0.0});
    theta0.push_back(ms_.theta(s0, i));
  }
  resolver_.emplace(esc, ms_.friction(), period_, theta0);
  if (ms_.coulomb()) {
    ev_s_ = &s0;
    resolver_->settleAtStart(*this);
    ev_s_ = nullptr;
  }
  ms_.system().realize(s0, Stage::Acceleration);
  return s0;
}

std::unique_ptr<Integrator> FullModelRun::makeRunIntegrator(const State& s0) {
  std::unique_ptr<Integrator> integ = makeSimbodyIntegrator(report_.integrator, ms_.system());
  integ->setAccuracy(rig_.sim.accuracy);
  integ->setFinalTime(rig_.sim.t_end_s);
  integ->setReturnEveryInternalStep(true);
  // witnesses that cross twice in one step are missed; the pendulums normally keep steps far
  // below this, but a stuck platform with dead pendulums would not
  integ->setMaximumStepSize(period_ / 8);
  integ->initialize(s0);
  return integ;
}

bool FullModelRun::checkNewStep(Integrator& integ, Integrator::SuccessfulStepStatus status) {
  const State& adv = integ.getAdvancedState();
  if (!allFinite(adv.getY())) {
    fail(adv.getTime(), "non-finite state");
    return false;
  }
  captureStepEnd(adv, cur_);
  const PlatformMode mode = ms_.coulomb() ? ms_.coulomb()->mode(adv) : PlatformMode::Stuck;
  const bool event_step = status == Integrator::ReachedEventTrigger;
  if (guard_depth_ < 5 && cur_.t - prev_.t > 1e-12 * period_ &&
      grazingMissed(prev_, cur_, mode, event_step)) {
    redoStep(integ);
    return true;
  }
  if (ms_.coulomb() && mode != PlatformMode::Stuck && static_cast<int>(mode) * cur_.v < 0 &&
      !event_step) {
    // still inconsistent at the finest step: the slip ended inside this step; stop now
    if (debug_) std::fprintf(stderr, "forced stop at %.9g v %g\n", cur_.t, cur_.v);
    noteDiscontinuity(cur_.t);
    pending_.platform = true;
    const Stage lowest = resolveWindow(integ.updAdvancedState());
    integ.reinitialize(lowest < Stage::Infinity ? lowest : Stage::Report, false);
    captureStepEnd(integ.getAdvancedState(), cur_);
  }
  if (guard_depth_ > 0 && cur_.t >= guard_until_) {
    guard_depth_ = 0;
    integ.setMaximumStepSize(period_ / 8);
  }
  prev_ = cur_;
  checked_until_ = cur_.t;
  return false;
}

// Redoes the step just taken from its start with steps 8 times smaller.
void FullModelRun::redoStep(Integrator& integ) {
  const double h = cur_.t - prev_.t;
  steps_base_ += integ.getNumStepsTaken();
  const long evals_before = integ.getNumRealizations();
  State back = integ.getAdvancedState();
  back.setTime(prev_.t);
  back.updY() = prev_.y;
  ms_.system().realize(back, Stage::Acceleration);
  integ.setMaximumStepSize(std::max(h / 8, 1e-14 * period_));
  guard_until_ = cur_.t;
  ++guard_depth_;
  ++rewinds_;
  noteDiscontinuity(cur_.t);
  if (!report_.complete) return;
  if (debug_) std::fprintf(stderr, "rewind %.9g..%.9g depth %d\n", prev_.t, cur_.t, guard_depth_);
  integ.initialize(back);
  evals_base_ += evals_before - integ.getNumRealizations();
  checked_until_ = prev_.t;
}

bool FullModelRun::windowIsLive() const {
  if (pending_.platform) return true;
  for (const auto& [i, side] : pending_.ticks)
    if (resolver_->armed(i, side)) return true;
  return false;
}

// Every triggered witness reports, then the resolver acts once on the whole window.
void FullModelRun::handleTrigger(Integrator& integ) {
  State& adv = integ.updAdvancedState();
  HandleEventsOptions opts(integ.getAccuracyInUse());
  HandleEventsResults results;
  ms_.system().handleEvents(adv, Event::Cause::Triggered, integ.getTriggeredEvents(), opts,
                            results);
  if (!windowIsLive()) {
    pending_.clear();
    return;
  }
  ++report_.counts.events;
  recordEnvelope(integ.getState(), integ.getTime());  // the last state before the event
  if (debug_)
    std::fprintf(stderr, "event at %.9g mode %d\n", adv.getTime(),
                 ms_.coulomb() ? static_cast<int>(ms_.coulomb()->mode(adv)) : 9);
  const Stage lowest = resolveWindow(adv);
  integ.reinitialize(lowest < Stage::Infinity ? lowest : Stage::Report, false);
  recordEnvelope(integ.getAdvancedState(), integ.getAdvancedTime());  // and the first after it
  captureStepEnd(integ.getAdvancedState(), prev_);
  checked_until_ = integ.getAdvancedTime();
  noteDiscontinuity(adv.getTime());
}

Stage FullModelRun::resolveWindow(State& s) {
  ms_.system().realize(s, Stage::Acceleration);
  ev_s_ = &s;
  const WindowOutcome out = resolver_->resolve(*this, pending_.platform);
  ev_s_ = nullptr;
  pending_.clear();
  for (int i : out.ticked) ++report_.counts.escapements[i];
  report_.counts.stick_slip += out.stick_slip;
  report_.counts.slip_reversals += out.slip_reversals;
  report_.ledger.escapement_in_J += out.escapement_in;
  report_.ledger.friction_out_J += out.friction_out;
  if (!out.changed()) return Stage::Infinity;
  ms_.system().realize(s, Stage::Acceleration);
  return out.stick_slip || out.slip_reversals || out.plastic_stops || ms_.coulomb()
             ? Stage::Model
             : Stage::Velocity;
}

// The samples due up to t_limit (inclusive), from the integrator's interpolated state.
void FullModelRun::takeSamples(const Integrator& integ, double t_limit) {
  schedule_->takeDue(t_limit, true, [&](double ts, bool row, bool env) {
    if (row) recordTrajectory(integ.getState(), ts);
    if (env) recordEnvelope(integ.getState(), ts);
  });
}

void FullModelRun::recordTrajectory(const State& s, double t) {
  RecordingScope rec(timer_);
  std::vector<double> row = makeRow(s, t);
  sink_.trajectoryRow(row);
  report_.final_trajectory_row = std::move(row);
}

void FullModelRun::eventRow(const char* kind, const State& s) {
  RecordingScope rec(timer_);
  sink_.eventRow(kind, makeRow(s, s.getTime()));
}

std::vector<double> FullModelRun::makeRow(const State& s, double t) const {
  std::vector<double> row;
  row.reserve(4 + 2 * n_);
  const bool scaled = rig_.units == Units::Scaled;
  const double xs = scaled ? 1.0 / sp_.x_scale_m : 1.0;
  const double as = scaled ? 1.0 / sp_.angle_scale : 1.0;
  const double ts = scaled ? omega0_ : 1.0;
  row.push_back(t * ts);
  row.push_back(ms_.x(s) * xs);
  row.push_back(ms_.xdot(s) * xs / ts);
  for (int i = 0; i < n_; ++i) {
    row.push_back(ms_.theta(s, i) * as);
    row.push_back(ms_.thetadot(s, i) * as / ts);
  }
  row.push_back(platformColumn(s));
  return row;
}

void FullModelRun::recordEnvelope(const State& s, double t) {
  RecordingScope rec(timer_);
  scratch_th_.resize(n_);
  scratch_w_.resize(n_);
  for (int i = 0; i < n_; ++i) {
    scratch_th_[i] = ms_.theta(s, i) / sp_.angle_scale;
    scratch_w_[i] = ms_.thetadot(s, i) / (sp_.angle_scale * omega0_);
  }
  env_.sample(t * omega0_, scratch_th_.data(), scratch_w_.data());
}

void FullModelRun::captureStepEnd(const State& s, StepEnd& e) {
  e.t = s.getTime();
  e.y = s.getY();
  e.th.resize(n_);
  e.w.resize(n_);
  for (int i = 0; i < n_; ++i) {
    e.th[i] = ms_.theta(s, i);
    e.w[i] = ms_.thetadot(s, i);
    resolver_->rearm(i, e.th[i]);  // a tick side is armed again once back inside theta_c
  }
  if (ms_.coulomb()) {
    e.v = ms_.xdot(s);
    e.a = ms_.slider().getOneUDot(s, MobilizerUIndex(0));
  }
}

bool FullModelRun::grazingMissed(const StepEnd& a, const StepEnd& b, PlatformMode mode,
                                 bool event_step) const {
  const double h = b.t - a.t;
  if (!(h > 0)) return false;
  for (int i = 0; i < n_; ++i) {
    if (!ms_.swings(i) || !(rig_.metronomes[i].impulse_Nms > 0)) continue;
    if (a.w[i] * b.w[i] >= 0) continue;  // no turning point inside the step
    const double tc = rig_.metronomes[i].theta_c_rad;
    const bool at_max = a.w[i] > 0;  // turning at a maximum of theta
    const double side = at_max ? 1.0 : -1.0;
    // both ends inside the critical angle on this side: a double crossing would be invisible
    if (side * a.th[i] >= tc || side * b.th[i] >= tc) continue;
    const double ext = side * hermiteInteriorExtreme(a.th[i], a.w[i], b.th[i], b.w[i], h, at_max);
    // margin: well above the cubic's own error (the rates at the ends are O(h) near a turn)
    const double margin = 1e-6 * tc + 1e-3 * h * (std::abs(a.w[i]) + std::abs(b.w[i]));
    if (ext > tc - margin) return true;
  }
  if (mode != PlatformMode::Stuck && ms_.coulomb()) {
    const double sgn = static_cast<int>(mode);
    // a slip that started from rest (witness at zero: Simbody does not report a transition away
    // from zero) and ended inside its first step
    // (a step that ends on the platform's own event has crossed zero by design)
    if (sgn * b.v < 0 && !event_step) return true;
    if (sgn * a.v > 0 && sgn * b.v > 0) {
      // a dip of the speed inside the step (not the monotone approach to a stop, which the
      // witness sees) that comes close to zero
      const double low = sgn * hermiteInteriorExtreme(a.v, a.a, b.v, b.a, h, sgn < 0);
      const double margin = 1e-3 * h * std::abs(a.a - b.a);
      if (low < margin) return true;
    }
  }
  return false;
}

RunReport FullModelRun::run() {
  timer_ = SplitTimer();
  const double t_end = rig_.sim.t_end_s;
  schedule_.emplace(rig_.sim.sample_s, period_, t_end);
  storm_.emplace(period_);
  State s0 = startState();
  report_.ledger.initial_J = energy(s0);
  std::unique_ptr<Integrator> integ = makeRunIntegrator(s0);
  recordTrajectory(integ->getState(), 0.0);
  recordEnvelope(integ->getState(), 0.0);
  captureStepEnd(integ->getAdvancedState(), prev_);
  checked_until_ = integ->getAdvancedTime();

  try {
    while (true) {
      // samples due at or before the current time (possible right after an event)
      takeSamples(*integ, integ->getTime());
      if (integ->getTime() >= t_end) break;
      const Integrator::SuccessfulStepStatus status = integ->stepTo(schedule_->next(), t_end);
      // a new step has been taken: check it before anything from it is recorded
      if (integ->getAdvancedTime() > checked_until_ && checkNewStep(*integ, status)) {
        if (!report_.complete) break;
        continue;
      }
      if (!report_.complete) break;
      switch (status) {
        case Integrator::ReachedReportTime:
        case Integrator::ReachedScheduledEvent:
        case Integrator::EndOfSimulation:
          takeSamples(*integ, integ->getTime());
          break;
        case Integrator::ReachedEventTrigger:
          handleTrigger(*integ);
          break;
        default:
          break;
      }
      if (!report_.complete) break;
      if (integ->isSimulationOver()) break;
    }
  } catch (const std::exception& e) {
    fail(integ->getAdvancedTime(), e.what());
  }

  // the end of the run: last trajectory row and the period it closes
  const State& fin = integ->getState();
  const double t_fin = fin.getTime();
  recordTrajectory(fin, t_fin);
  recordEnvelope(fin, t_fin);
  report_.final_row = env_.finish();  // the last period ending at t_fin (SPEC 3 final)

  report_.counts.steps = steps_base_ + integ->getNumStepsTaken();
  report_.counts.rhs_evals = evals_base_ + integ->getNumRealizations();
  report_.ledger.final_J = energy(fin);
  report_.ledger.damping_out_J = ms_.meter().dampingLoss(fin);
  report_.ledger.friction_out_J += ms_.meter().frictionLoss(fin);
  report_.has_ledger = true;
  if (std::getenv("METROSYNC_DEBUG"))
    std::fprintf(stderr, "debug: rewinds %ld steps %d attempts %d realizations %d\n", rewinds_,
                 integ->getNumStepsTaken(), integ->getNumStepsAttempted(),
                 integ->getNumRealizations());
  report_.wall_seconds = timer_.wallSeconds();
  report_.engine_seconds = report_.wall_seconds - timer_.recordingSeconds(report_.wall_seconds);
  return report_;
}

}  // namespace

RunReport runFullModel(const Rig& rig, RunSink& sink) {
  FullModelRun run(rig, sink);
  return run.run();
}

}  // namespace metrosync
