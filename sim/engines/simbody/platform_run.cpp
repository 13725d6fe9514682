// The Simbody engine's one run loop (platform_run.h). The pieces, top to bottom:
//   1. witnesses (sim/events/witness.h, directions from their types): thin
//      TriggeredEventHandlers that only say "my witness crossed": a tick per pendulum and side
//      (rising side * theta_j - theta_c), a stick margin or slip velocity per Coulomb contact.
//      Simbody calls every handler whose witness crossed in the localization window, in
//      registration order, on the same state; so none of them acts.
//   2. the window, resolved on its end state through the shared resolver (sim/events/resolver.h),
//      one EventResolver per platform over a view of the Simbody state (its pendulums, the
//      contact under it), in file order: every due tick as one combined impulse through the mass
//      matrix with every contact free, then the platform's Coulomb rule; then the platforms whose
//      support an impulse moved (EventResolver::settleAfterSupportImpulse). The result does not
//      depend on the order in which Simbody called the handlers. A window whose only reports are
//      consumed ticks (applied inside their slack) is not an event.
//   3. a stuck contact is an acceleration lock on its slider (contact/simbody/coulomb_contact.h):
//      Simbody solves every stuck contact's holding force at once; an impulse lifts the locks for
//      its M^-1 (a locked mobility would get no velocity change) and puts them back.
//   4. the grazing guard (grazing_guard.h): a step that may have hidden a double crossing is
//      redone with smaller steps; a slip that ended inside its step is stopped at its end.
//   5. samples by interpolation on the shared schedule (sim/events/sample_schedule.h: the
//      integrator is never forced to stop at a sample), handed to the caller's RunRecorder; the
//      shared storm rule (sim/events/storm_guard.h).
#include "sim/engines/simbody/platform_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>

#include "base/constants.h"
#include "models/simbody/platform_system.h"
#include "sim/engines/simbody/grazing_guard.h"
#include "sim/engines/simbody/integrators.h"
#include "sim/events/resolver.h"
#include "sim/events/sample_schedule.h"
#include "sim/events/storm_guard.h"
#include "sim/events/witness.h"
#include "sim/record/split_timer.h"

namespace metrosync {

using namespace SimTK;

namespace {

// The longest step, in fast periods: witnesses that cross twice in one step are missed; the
// pendulums normally keep steps far below this, but a stuck platform with dead pendulums would
// not (the grazing guard catches what is left).
constexpr double kMaxStepPeriods = 1.0 / 8;
// A step the grazing guard rejects is redone from its start with steps this many times smaller,
// at most kMaxRedoDepth times in a row; a step shorter than kMinGuardedPeriods of a period is
// not checked (nothing can turn inside it); a redo never steps below kMinRedoPeriods.
constexpr double kRedoShrink = 8.0;
constexpr int kMaxRedoDepth = 5;
constexpr double kMinGuardedPeriods = 1e-12;
constexpr double kMinRedoPeriods = 1e-14;
// Resolution passes per event window: each pass settles the platforms whose support moved; a
// stack of P platforms needs at most P passes.
constexpr int kSettlePassesPerPlatform = 2;

// What the witnesses reported in one localization window.
struct Pending {
  std::vector<std::pair<int, int>> ticks;  // (pendulum, side), network numbering
  std::vector<char> contacts;              // (platforms) the contact's witness crossed
  void clear() {
    ticks.clear();
    std::fill(contacts.begin(), contacts.end(), 0);
  }
};

void setDirection(TriggeredEventHandler& h, Direction d) {
  h.getTriggerInfo().setTriggerOnRisingSignTransition(d != Direction::Falling);
  h.getTriggerInfo().setTriggerOnFallingSignTransition(d != Direction::Rising);
}

class TickHandler : public TriggeredEventHandler {
 public:
  TickHandler(const PlatformSystem& ps, int j, int side, Pending& pending)
      : TriggeredEventHandler(Stage::Position),
        ps_(ps),
        w_{j, side},
        esc_(ps.equations().escapement(j)),
        pending_(pending) {
    setDirection(*this, TickWitness::kDirection);
  }
  Real getValue(const State& s) const override { return w_.value(esc_, ps_.theta(s, w_.pendulum)); }
  void handleEvent(State&, Real, bool&) const override {
    pending_.ticks.emplace_back(w_.pendulum, w_.side);
  }

 private:
  const PlatformSystem& ps_;
  TickWitness w_;
  Escapement esc_;
  Pending& pending_;
};

class ContactHandler : public TriggeredEventHandler {
 public:
  ContactHandler(const PlatformSystem& ps, int p, Pending& pending)
      : TriggeredEventHandler(Stage::Acceleration), ps_(ps), p_(p), pending_(pending) {
    setDirection(*this, PlatformWitness::kDirection);
  }
  // the contact's witness is PlatformWitness::value (stick margin / mode * slip velocity)
  Real getValue(const State& s) const override { return ps_.contact(p_)->witness(s); }
  void handleEvent(State&, Real, bool&) const override { pending_.contacts[p_] = 1; }

 private:
  const PlatformSystem& ps_;
  int p_;
  Pending& pending_;
};

bool allFinite(const Vector& y) {
  for (int k = 0; k < y.size(); ++k)
    if (!std::isfinite(y[k])) return false;
  return true;
}

// M^-1 f with every contact free: dry friction gives no impulse (docs/events.md), so the locks of
// the stuck contacts are lifted for the product (multiplyByMInv gives a locked mobility no
// velocity change) and put back (at acceleration level: no velocity is touched by them).
Vector freeMInv(const PlatformSystem& ps, State& s, const Vector& f) {
  std::vector<int> held;
  for (int p = 0; p < ps.numPlatforms(); ++p)
    if (ps.moves(p) && ps.slider(p).isLocked(s)) {
      ps.slider(p).unlock(s);
      held.push_back(p);
    }
  ps.system().realize(s, Stage::Position);
  Vector du;
  ps.matter().multiplyByMInv(s, f, du);
  for (int p : held) ps.slider(p).lock(s, Motion::Acceleration);
  return du;
}

double energy(const PlatformSystem& ps, const State& s) {
  ps.system().realize(s, Stage::Velocity);
  return ps.system().calcEnergy(s);
}

class PlatformRun;

// One platform seen by the shared resolver, on the run's event state: its pendulums, the contact
// under it.
class ContactView : public EventSystem {
 public:
  ContactView(PlatformSystem& ps, PlatformRun& run, State*& s, int p)
      : ps_(ps), run_(run), s_(s), p_(p), block_(ps.equations().block(p)) {}
  double theta(int j) const override { return ps_.theta(*s_, block_.first + j); }
  double thetadot(int j) const override { return ps_.thetadot(*s_, block_.first + j); }
  double xdot() const override { return ps_.slipVelocity(*s_, p_); }
  PlatformMode mode() const override { return ps_.contact(p_)->mode(*s_); }
  void setMode(PlatformMode m) override;
  double holdingForce() override {
    ps_.system().realize(*s_, Stage::Acceleration);
    return ps_.contact(p_)->holdingForce(*s_);
  }
  double applyImpulse(const std::vector<double>& pin, double contact) override;
  double platformMobility() override;
  void eventRow(const char* kind) override;
  void snapshotBefore() override;
  void recordEvent(const char* kind, int j) override;

 private:
  PlatformSystem& ps_;
  PlatformRun& run_;
  State*& s_;
  int p_;
  const network::Block& block_;
};

// Stuck: the resolver calls it once the slip velocity is 0 to rounding (after a plastic stop, or
// exactly 0); the rounding stays until the window ends (stickAtRest).
void ContactView::setMode(PlatformMode m) {
  State& s = *s_;
  ps_.contact(p_)->setMode(s, m);
  ps_.system().realize(s, Stage::Velocity);
}

// pin[j] on the platform's pendulum j, `contact` on its slider (on it, and its opposite on the
// platform below): one generalized impulse through the mass matrix, every contact free. Returns
// the kinetic energy jump (the potential energy does not jump).
double ContactView::applyImpulse(const std::vector<double>& pin, double contact) {
  State& s = *s_;
  ps_.system().realize(s, Stage::Position);
  const double e0 = energy(ps_, s);
  Vector f(s.getNU(), 0.0);
  for (int j = 0; j < block_.count; ++j)
    if (pin[j] != 0) ps_.pin(block_.first + j).applyOneMobilityForce(s, 0, pin[j], f);
  if (contact != 0 && ps_.moves(p_)) ps_.slider(p_).applyOneMobilityForce(s, 0, contact, f);
  s.updU() += freeMInv(ps_, s, f);
  ps_.system().realize(s, Stage::Velocity);
  return energy(ps_, s) - e0;
}

double ContactView::platformMobility() {
  State& s = *s_;
  ps_.system().realize(s, Stage::Position);
  Vector f(s.getNU(), 0.0);
  ps_.slider(p_).applyOneMobilityForce(s, 0, 1.0, f);
  const Vector du = freeMInv(ps_, s, f);
  return ps_.slider(p_).getOneFromUPartition(s, 0, du);
}

// The run: Simbody's integrator, thin witnesses, and the shared resolvers acting on the event
// state through the platforms' views.
class PlatformRun {
 public:
  PlatformRun(PlatformSystem& ps, const std::string& integrator, double time_scale_s,
              RunRecorder& recorder);
  PlatformRunResult run();

  // the views' recording (on the event state)
  void eventRow(const char* kind) {
    ++result_.event_rows;
    RecordingScope rec(timer_);
    rec_.eventRow(kind, *ev_s_);
  }
  void snapshotBefore() {
    if (!rec_.wantsEventRecords()) return;
    RecordingScope rec(timer_);
    rec_.snapshotBefore(*ev_s_);
  }
  void recordEvent(const char* kind, int p, int j) {
    if (!rec_.wantsEventRecords()) return;
    RecordingScope rec(timer_);
    const int metronome = j < 0 ? -1 : ps_.equations().pendulum(eq_first(p) + j).rig_index;
    rec_.recordEvent(kind, metronome, *ev_s_);
  }

 private:
  int eq_first(int p) const { return ps_.equations().block(p).first; }
  State startState();
  std::unique_ptr<Integrator> makeRunIntegrator(const State& s0);
  // Checks a step just taken: grazing (redo it smaller), a slip that ended inside it (stop).
  // Returns true when the step was redone.
  bool checkNewStep(Integrator& integ, Integrator::SuccessfulStepStatus status);
  bool grazingMissed(const State& adv, bool event_step) const;
  bool slipAgainstMode(const State& s);
  void stopInsideStep(Integrator& integ);
  void redoStep(Integrator& integ);
  void handleTrigger(Integrator& integ);
  bool windowIsLive() const;
  Stage resolveWindow(State& s);  // the resolvers on s; the lowest stage they changed
  bool settleSupports(State& s);
  void stickAtRest(State& s);
  void absorb(const WindowOutcome& out, int p);
  void takeSamples(Integrator& integ, double t_limit, bool interpolate);
  void captureStepEnd(const State& s, StepEnd& e);
  void fail(double t, const std::string& why) {
    if (!result_.complete) return;
    result_.complete = false;
    result_.failure = rec_.failureText(t, why);
  }
  void noteDiscontinuity(double t) {
    if (storm_->note(t)) fail(t, storm_->why());
  }

  PlatformSystem& ps_;
  const network::NetworkEquations& eq_;
  RunRecorder& rec_;
  std::string integrator_;
  SplitTimer timer_;  // the engine's time against the recording's
  Pending pending_;
  PlatformRunResult result_;
  double period_ = 1;  // fast period, seconds
  double t_end_ = 0;
  std::vector<std::unique_ptr<ContactView>> views_;
  std::vector<EventResolver> resolvers_;
  std::optional<SampleSchedule> schedule_;
  std::optional<StormGuard> storm_;
  State* ev_s_ = nullptr;  // the state the resolvers act on
  // grazing guard: the last checked step end, and the state of a redo
  StepEnd prev_, cur_;
  Vector prev_y_;
  double checked_until_ = 0.0;
  double guard_until_ = -1;  // while redoing a grazing step: time until which hmax is reduced
  int guard_depth_ = 0;
  long steps_base_ = 0, evals_base_ = 0, rewinds_ = 0;
  int moving_platforms_ = 0;
  bool debug_ = std::getenv("METROSYNC_DEBUG") != nullptr;
};

void ContactView::eventRow(const char* kind) {
  run_.eventRow(kind);
}
void ContactView::snapshotBefore() {
  run_.snapshotBefore();
}
void ContactView::recordEvent(const char* kind, int j) {
  run_.recordEvent(kind, p_, j);
}

PlatformRun::PlatformRun(PlatformSystem& ps, const std::string& integrator, double time_scale_s,
                         RunRecorder& recorder)
    : ps_(ps), eq_(ps.equations()), rec_(recorder), integrator_(integrator) {
  const double omega0 = 1.0 / time_scale_s;
  period_ = 2 * kPi / omega0;
  t_end_ = ps.network().sim.t_end_s;
  result_.counts.escapements.assign(ps.network().numMetronomes(), 0);
  const int np = ps.numPlatforms();
  pending_.contacts.assign(np, 0);
  for (int p = 0; p < np; ++p) moving_platforms_ += ps.moves(p);
  // witnesses: only what the scene needs
  for (int j = 0; j < ps.numPendulums(); ++j)
    if (eq_.escapement(j).impulse > 0)
      for (int side : {1, -1}) ps.system().addEventHandler(new TickHandler(ps, j, side, pending_));
  for (int p = 0; p < np; ++p)
    if (ps.contact(p)) ps.system().addEventHandler(new ContactHandler(ps, p, pending_));
  ps.system().setDefaultTimeScale(time_scale_s);
  ps.system().realizeTopology();
  for (int p = 0; p < np; ++p) views_.push_back(std::make_unique<ContactView>(ps, *this, ev_s_, p));
}

// The start state, the resolvers armed by it, and every Coulomb contact's mode decided at rest
// in file order, the later ones held meanwhile.
State PlatformRun::startState() {
  State s0 = ps_.initialState();
  for (int p = 0; p < ps_.numPlatforms(); ++p) {
    const network::Block& b = eq_.block(p);
    std::vector<Escapement> esc;
    std::vector<double> th0;
    for (int j = b.first; j < b.first + b.count; ++j) {
      esc.push_back(eq_.escapement(j));
      th0.push_back(ps_.theta(s0, j));
    }
    resolvers_.emplace_back(esc, b.friction, period_, th0);
  }
  for (int p = 0; p < ps_.numPlatforms(); ++p)
    if (ps_.contact(p)) ps_.contact(p)->setMode(s0, PlatformMode::Stuck);
  ev_s_ = &s0;
  for (int p = 0; p < ps_.numPlatforms(); ++p)
    if (ps_.contact(p)) resolvers_[p].settleAtStart(*views_[p]);
  ev_s_ = nullptr;
  ps_.system().realize(s0, Stage::Acceleration);
  return s0;
}

std::unique_ptr<Integrator> PlatformRun::makeRunIntegrator(const State& s0) {
  std::unique_ptr<Integrator> integ = makeSimbodyIntegrator(integrator_, ps_.system());
  integ->setAccuracy(ps_.network().sim.accuracy);
  integ->setFinalTime(t_end_);
  integ->setReturnEveryInternalStep(true);
  integ->setMaximumStepSize(kMaxStepPeriods * period_);
  integ->initialize(s0);
  return integ;
}

void PlatformRun::captureStepEnd(const State& s, StepEnd& e) {
  e.t = s.getTime();
  const int n = ps_.numPendulums(), np = ps_.numPlatforms();
  e.th.resize(n);
  e.w.resize(n);
  for (int j = 0; j < n; ++j) {
    e.th[j] = ps_.theta(s, j);
    e.w[j] = ps_.thetadot(s, j);
    // a tick side is armed again once back inside theta_c
    const int p = ps_.platformOf(j);
    resolvers_[p].rearm(j - eq_.block(p).first, e.th[j]);
  }
  e.v.assign(np, 0.0);
  e.a.assign(np, 0.0);
  for (int p = 0; p < np; ++p)
    if (ps_.contact(p)) {
      e.v[p] = ps_.slipVelocity(s, p);
      e.a[p] = ps_.slider(p).getOneUDot(s, MobilizerUIndex(0));
    }
}

bool PlatformRun::grazingMissed(const State& adv, bool event_step) const {
  if (!(cur_.t - prev_.t > 0)) return false;
  for (int j = 0; j < ps_.numPendulums(); ++j)
    if (eq_.escapement(j).impulse > 0 && tickGrazed(prev_, cur_, j, eq_.escapement(j))) return true;
  for (int p = 0; p < ps_.numPlatforms(); ++p) {
    const CoulombContact* c = ps_.contact(p);
    if (!c || c->mode(adv) == PlatformMode::Stuck) continue;
    if (slipGrazed(prev_, cur_, p, c->mode(adv), event_step)) return true;
  }
  return false;
}

// Marks every slip running against its mode in s (pending_), and says whether there is one.
bool PlatformRun::slipAgainstMode(const State& s) {
  bool against = false;
  for (int p = 0; p < ps_.numPlatforms(); ++p) {
    const CoulombContact* c = ps_.contact(p);
    if (!c || c->mode(s) == PlatformMode::Stuck) continue;
    if (static_cast<int>(c->mode(s)) * c->slipVelocity(s) < 0) {
      pending_.contacts[p] = 1;
      against = true;
    }
  }
  return against;
}

bool PlatformRun::checkNewStep(Integrator& integ, Integrator::SuccessfulStepStatus status) {
  const State& adv = integ.getAdvancedState();
  if (!allFinite(adv.getY())) {
    fail(adv.getTime(), "non-finite state");
    return false;
  }
  captureStepEnd(adv, cur_);
  const bool event_step = status == Integrator::ReachedEventTrigger;
  if (guard_depth_ < kMaxRedoDepth && cur_.t - prev_.t > kMinGuardedPeriods * period_ &&
      grazingMissed(adv, event_step)) {
    redoStep(integ);
    return true;
  }
  {
    RecordingScope rec(timer_);
    rec_.stretchTo(adv);  // the step is kept: the trajectory up to its end
  }
  // still inconsistent at the finest step: the slip ended inside this step; stop it at its end
  if (!event_step && slipAgainstMode(adv)) stopInsideStep(integ);
  if (guard_depth_ > 0 && cur_.t >= guard_until_) {
    guard_depth_ = 0;
    integ.setMaximumStepSize(kMaxStepPeriods * period_);
  }
  prev_ = cur_;
  prev_y_ = integ.getAdvancedState().getY();
  checked_until_ = cur_.t;
  return false;
}

// The samples inside the step first, from its interpolant; then the stop at the step's end.
void PlatformRun::stopInsideStep(Integrator& integ) {
  if (debug_) std::fprintf(stderr, "forced stop at %.9g\n", cur_.t);
  takeSamples(integ, integ.getAdvancedTime(), true);
  ++result_.forced_stops;
  noteDiscontinuity(cur_.t);
  const Stage lowest = resolveWindow(integ.updAdvancedState());
  integ.reinitialize(lowest < Stage::Infinity ? lowest : Stage::Report, false);
  {
    RecordingScope rec(timer_);
    rec_.restartAt(integ.getAdvancedState());
  }
  captureStepEnd(integ.getAdvancedState(), cur_);
}

// Redoes the step just taken from its start with steps kRedoShrink times smaller.
void PlatformRun::redoStep(Integrator& integ) {
  const double h = cur_.t - prev_.t;
  pending_.clear();
  steps_base_ += integ.getNumStepsTaken();
  const long evals_before = integ.getNumRealizations();
  State back = integ.getAdvancedState();
  back.setTime(prev_.t);
  back.updY() = prev_y_;
  ps_.system().realize(back, Stage::Acceleration);
  integ.setMaximumStepSize(std::max(h / kRedoShrink, kMinRedoPeriods * period_));
  guard_until_ = cur_.t;
  ++guard_depth_;
  ++rewinds_;
  noteDiscontinuity(cur_.t);
  if (!result_.complete) return;
  if (debug_) std::fprintf(stderr, "rewind %.9g..%.9g depth %d\n", prev_.t, cur_.t, guard_depth_);
  integ.initialize(back);
  evals_base_ += evals_before - integ.getNumRealizations();
  checked_until_ = prev_.t;
}

bool PlatformRun::windowIsLive() const {
  for (char c : pending_.contacts)
    if (c) return true;
  for (const auto& [j, side] : pending_.ticks) {
    const int p = ps_.platformOf(j);
    if (resolvers_[p].armed(j - eq_.block(p).first, side)) return true;
  }
  return false;
}

// Every triggered witness reports, then the resolvers act once on the whole window.
void PlatformRun::handleTrigger(Integrator& integ) {
  State& adv = integ.updAdvancedState();
  HandleEventsOptions opts(integ.getAccuracyInUse());
  HandleEventsResults results;
  ps_.system().handleEvents(adv, Event::Cause::Triggered, integ.getTriggeredEvents(), opts,
                            results);
  if (!windowIsLive()) {
    pending_.clear();
    return;
  }
  ++result_.counts.events;
  if (debug_)
    std::fprintf(stderr, "event at %.9g mode %d\n", adv.getTime(),
                 ps_.contact(0) ? static_cast<int>(ps_.contact(0)->mode(adv)) : 9);
  const Stage lowest = resolveWindow(adv);
  integ.reinitialize(lowest < Stage::Infinity ? lowest : Stage::Report, false);
  {
    RecordingScope rec(timer_);
    rec_.restartAt(integ.getAdvancedState());  // the first state after the event
  }
  captureStepEnd(integ.getAdvancedState(), prev_);
  prev_y_ = integ.getAdvancedState().getY();
  checked_until_ = integ.getAdvancedTime();
  noteDiscontinuity(adv.getTime());
}

void PlatformRun::absorb(const WindowOutcome& out, int p) {
  for (int j : out.ticked)
    ++result_.counts.escapements[eq_.pendulum(eq_.block(p).first + j).rig_index];
  result_.counts.stick_slip += out.stick_slip;
  result_.counts.slip_reversals += out.slip_reversals;
  result_.ledger.escapement_in_J += out.escapement_in;
  result_.ledger.friction_out_J += out.friction_out;
}

// Each platform's resolver in file order (a contact counts as reported when its witness has
// crossed: the stick margins judged on the window's state before any impulse, the slip
// velocities when the platform's turn comes), then the supports. Returns the lowest stage changed.
Stage PlatformRun::resolveWindow(State& s) {
  ps_.system().realize(s, Stage::Acceleration);
  ev_s_ = &s;
  const int np = ps_.numPlatforms();
  std::vector<double> margin(np, 1.0);
  bool any_contact = false;
  for (int p = 0; p < np; ++p)
    if (ps_.contact(p)) {
      any_contact = true;
      if (ps_.contact(p)->mode(s) == PlatformMode::Stuck) margin[p] = ps_.contact(p)->witness(s);
    }
  bool changed = false;
  for (int p = 0; p < np; ++p) {
    const CoulombContact* c = ps_.contact(p);
    bool reported = false;
    if (c) {
      const PlatformMode m = c->mode(s);
      const double g =
          m == PlatformMode::Stuck ? margin[p] : static_cast<int>(m) * c->slipVelocity(s);
      reported = pending_.contacts[p] || g <= 0;
    }
    const WindowOutcome out = resolvers_[p].resolve(*views_[p], reported);
    absorb(out, p);
    changed = changed || out.changed();
  }
  if (settleSupports(s)) changed = true;  // (only where a platform can move another's support)
  stickAtRest(s);
  ev_s_ = nullptr;
  pending_.clear();
  if (!changed) return Stage::Infinity;
  ps_.system().realize(s, Stage::Acceleration);
  return any_contact ? Stage::Model : Stage::Velocity;
}

// Every contact the window leaves stuck rests exactly: the rounding its plastic stop left in its
// slip velocity (O(1e-16) of the velocity it stopped from; the stop's reaction is applied) is
// dropped, as a lock at zero velocity would, so that a stuck board does not creep.
void PlatformRun::stickAtRest(State& s) {
  for (int p = 0; p < ps_.numPlatforms(); ++p) {
    const CoulombContact* c = ps_.contact(p);
    if (c && c->mode(s) == PlatformMode::Stuck && c->slipVelocity(s) != 0)
      ps_.slider(p).setOneU(s, MobilizerUIndex(0), 0.0);
  }
}

// Contacts the window's later changes left inconsistent: stuck with a velocity (an impulse
// below), stuck beyond the bound (another contact's switch or tick changed the forces on it), or
// slipping against their mode. Returns whether any was settled.
bool PlatformRun::settleSupports(State& s) {
  bool any = false;
  // with one moving platform no later turn changes a contact after its own: its resolver has left
  // it consistent (a slip from rest may carry its stop's rounding against its mode: not a switch)
  if (moving_platforms_ < 2) return any;
  for (int pass = 0; pass < kSettlePassesPerPlatform * ps_.numPlatforms(); ++pass) {
    bool changed = false;
    for (int p = 0; p < ps_.numPlatforms(); ++p) {
      const CoulombContact* c = ps_.contact(p);
      if (!c) continue;
      const double u = c->slipVelocity(s);
      const PlatformMode m = c->mode(s);
      bool off = static_cast<int>(m) * u <= 0;
      if (m == PlatformMode::Stuck) {
        ps_.system().realize(s, Stage::Acceleration);
        off = u != 0 || c->law().breaksFree(c->holdingForce(s));
      }
      if (!off) continue;
      absorb(resolvers_[p].settleAfterSupportImpulse(*views_[p]), p);
      changed = any = true;
    }
    if (!changed) break;
  }
  return any;
}

// The samples due up to t_limit (inclusive), from the integrator's state; `interpolate`: each at
// its own time from the step's interpolant (else the state the integrator is at).
void PlatformRun::takeSamples(Integrator& integ, double t_limit, bool interpolate) {
  schedule_->takeDue(t_limit, true, [&](double ts, bool row, bool env) {
    if (interpolate && integ.getTime() < ts) integ.stepTo(ts, t_end_);
    RecordingScope rec(timer_);
    rec_.sample(integ.getState(), ts, row, env);
  });
}

PlatformRunResult PlatformRun::run() {
  timer_ = SplitTimer();
  schedule_.emplace(rec_.sampleInterval(), period_, t_end_);
  storm_.emplace(period_);
  State s0 = startState();
  result_.ledger.initial_J = energy(ps_, s0);
  std::unique_ptr<Integrator> integ = makeRunIntegrator(s0);
  {
    RecordingScope rec(timer_);
    rec_.sample(integ->getState(), 0.0, true, true);
    rec_.restartAt(integ->getState());
  }
  captureStepEnd(integ->getAdvancedState(), prev_);
  prev_y_ = integ->getAdvancedState().getY();
  checked_until_ = integ->getAdvancedTime();

  try {
    while (true) {
      // samples due at or before the current time (possible right after an event)
      takeSamples(*integ, integ->getTime(), false);
      if (integ->getTime() >= t_end_) break;
      const Integrator::SuccessfulStepStatus status = integ->stepTo(schedule_->next(), t_end_);
      rec_.poll(integ->getAdvancedTime());  // (a stop request between two rows)
      // a new step has been taken: check it before anything from it is recorded
      if (integ->getAdvancedTime() > checked_until_ && checkNewStep(*integ, status)) {
        if (!result_.complete) break;
        continue;
      }
      if (!result_.complete) break;
      if (status == Integrator::ReachedEventTrigger)
        handleTrigger(*integ);
      else if (status == Integrator::ReachedReportTime ||
               status == Integrator::ReachedScheduledEvent || status == Integrator::EndOfSimulation)
        takeSamples(*integ, integ->getTime(), false);
      if (!result_.complete || integ->isSimulationOver()) break;
    }
  } catch (const std::exception& e) {
    fail(integ->getAdvancedTime(), e.what());
  }

  const State& fin = integ->getState();
  {
    RecordingScope rec(timer_);
    rec_.finish(fin);
  }
  result_.t_end = fin.getTime();
  result_.counts.steps = steps_base_ + integ->getNumStepsTaken();
  result_.counts.rhs_evals = evals_base_ + integ->getNumRealizations();
  result_.ledger.final_J = energy(ps_, fin);
  result_.ledger.damping_out_J = ps_.dampingLoss(fin) + ps_.damperLoss(fin);
  result_.ledger.friction_out_J += ps_.frictionLoss(fin);
  if (debug_)
    std::fprintf(stderr, "debug: rewinds %ld steps %d attempts %d realizations %d\n", rewinds_,
                 integ->getNumStepsTaken(), integ->getNumStepsAttempted(),
                 integ->getNumRealizations());
  result_.wall_seconds = timer_.wallSeconds();
  result_.engine_seconds = result_.wall_seconds - timer_.recordingSeconds(result_.wall_seconds);
  return result_;
}

}  // namespace

PlatformRunResult runPlatforms(PlatformSystem& ps, const std::string& integrator,
                               double time_scale_s, RunRecorder& recorder) {
  PlatformRun run(ps, integrator, time_scale_s, recorder);
  return run.run();
}

}  // namespace metrosync
