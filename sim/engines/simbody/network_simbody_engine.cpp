// The network's run loop on Simbody. The pieces, top to bottom:
//   1. witnesses (sim/events/witness.h): thin TriggeredEventHandlers that only say "my witness
//      crossed": a tick per pendulum and side, a stick margin or slip velocity per Coulomb
//      contact. Simbody calls every handler whose witness crossed in the localization window, in
//      registration order, on the same state; so none of them acts.
//   2. the window, resolved as the direct network engine resolves it: per platform in file order
//      its EventResolver (ticks as one impulse through the full mass matrix with every contact
//      free, then its Coulomb rule), then the platforms whose support an impulse moved
//      (EventResolver::settleAfterSupportImpulse), until none is left.
//   3. a stuck contact is an acceleration lock on its slider (contact/simbody/coulomb_contact.h):
//      Simbody solves every stuck contact's holding force at once, and an impulse lifts the locks
//      for its M^-1 (a locked mobility would get no velocity change) and puts them back.
//   4. samples at the direct engine's times (simulation.sample, default period/20), from the
//      integrator's interpolant; steps at most kMaxStepPeriods of a fast period.
#include "sim/engines/simbody/network_simbody_engine.h"

#include <Simbody.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

#include "models/network_equations.h"
#include "models/scaling.h"
#include "models/simbody/network_system.h"
#include "sim/engines/simbody/integrators.h"
#include "sim/engines/simbody/simbody_engine.h"
#include "sim/events/resolver.h"
#include "sim/events/storm_guard.h"
#include "sim/events/witness.h"
#include "sim/record/split_timer.h"

namespace metrosync {

using namespace SimTK;

namespace {

// The longest step, in fast periods: the direct network engine's, so that a witness cannot cross
// and return within one step (a tick witness stays above zero for about a tenth of a period).
constexpr double kMaxStepPeriods = 0.05;
// A step that ends with a slip running against its mode (it started from rest, where Simbody
// reports no transition away from zero, and reversed inside the step) is redone from its start
// with steps this many times smaller, at most kMaxRedoDepth times in a row; then the slip is
// stopped at the step's end.
constexpr double kRedoShrink = 8.0;
constexpr int kMaxRedoDepth = 5;
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
  TickHandler(const NetworkSystem& ns, int j, int side, Pending& pending)
      : TriggeredEventHandler(Stage::Position),
        ns_(ns),
        w_{j, side},
        esc_(ns.equations().escapement(j)),
        pending_(pending) {
    setDirection(*this, TickWitness::kDirection);
  }
  Real getValue(const State& s) const override { return w_.value(esc_, ns_.theta(s, w_.pendulum)); }
  void handleEvent(State&, Real, bool&) const override {
    pending_.ticks.emplace_back(w_.pendulum, w_.side);
  }

 private:
  const NetworkSystem& ns_;
  TickWitness w_;
  Escapement esc_;
  Pending& pending_;
};

class ContactHandler : public TriggeredEventHandler {
 public:
  ContactHandler(const NetworkSystem& ns, int p, Pending& pending)
      : TriggeredEventHandler(Stage::Acceleration), ns_(ns), p_(p), pending_(pending) {
    setDirection(*this, PlatformWitness::kDirection);
  }
  Real getValue(const State& s) const override { return ns_.contact(p_)->witness(s); }
  void handleEvent(State&, Real, bool&) const override { pending_.contacts[p_] = 1; }

 private:
  const NetworkSystem& ns_;
  int p_;
  Pending& pending_;
};

// M^-1 f with every contact free: dry friction gives no impulse (docs/events.md), so the locks of
// the stuck contacts are lifted for the product (multiplyByMInv gives a locked mobility no
// velocity change) and put back (at acceleration level: no velocity is touched by them).
Vector freeMInv(const NetworkSystem& ns, State& s, const Vector& f) {
  std::vector<int> held;
  for (int p = 0; p < ns.numPlatforms(); ++p)
    if (ns.moves(p) && ns.slider(p).isLocked(s)) {
      ns.slider(p).unlock(s);
      held.push_back(p);
    }
  ns.system().realize(s, Stage::Position);
  Vector du;
  ns.matter().multiplyByMInv(s, f, du);
  for (int p : held) ns.slider(p).lock(s, Motion::Acceleration);
  return du;
}

// One platform seen by the shared resolver, on the run's event state: its pendulums, the contact
// under it.
class ContactView : public EventSystem {
 public:
  ContactView(const NetworkSystem& ns, State*& s, int p, long& rows)
      : ns_(ns), s_(s), p_(p), rows_(rows), block_(ns.equations().block(p)) {}
  double theta(int j) const override { return ns_.theta(*s_, block_.first + j); }
  double thetadot(int j) const override { return ns_.thetadot(*s_, block_.first + j); }
  double xdot() const override { return ns_.slipVelocity(*s_, p_); }
  PlatformMode mode() const override { return ns_.contact(p_)->mode(*s_); }
  void setMode(PlatformMode m) override { ns_.contact(p_)->setMode(*s_, m); }
  double holdingForce() override {
    ns_.system().realize(*s_, Stage::Acceleration);
    return ns_.contact(p_)->holdingForce(*s_);
  }
  double applyImpulse(const std::vector<double>& pin, double contact) override;
  double platformMobility() override {
    State& s = *s_;
    ns_.system().realize(s, Stage::Position);
    Vector f(s.getNU(), 0.0);
    ns_.slider(p_).applyOneMobilityForce(s, 0, 1.0, f);
    const Vector du = freeMInv(ns_, s, f);
    return ns_.slider(p_).getOneFromUPartition(s, 0, du);
  }
  void eventRow(const char*) override { ++rows_; }

 private:
  const NetworkSystem& ns_;
  State*& s_;
  int p_;
  long& rows_;
  const network::Block& block_;
};

// pin[j] on the platform's pendulum j, `contact` on its slider (on it, and its opposite on the
// platform below): one generalized impulse through the full mass matrix, every contact free.
// Returns the kinetic energy jump f . (u + du / 2).
double ContactView::applyImpulse(const std::vector<double>& pin, double contact) {
  State& s = *s_;
  ns_.system().realize(s, Stage::Position);
  Vector f(s.getNU(), 0.0);
  for (int j = 0; j < block_.count; ++j)
    if (pin[j] != 0) ns_.pin(block_.first + j).applyOneMobilityForce(s, 0, pin[j], f);
  if (contact != 0 && ns_.moves(p_)) ns_.slider(p_).applyOneMobilityForce(s, 0, contact, f);
  const Vector du = freeMInv(ns_, s, f);
  const Vector& u = s.getU();
  double dT = 0.0;
  for (int k = 0; k < f.size(); ++k) dT += f[k] * (u[k] + 0.5 * du[k]);
  s.updU() += du;
  ns_.system().realize(s, Stage::Velocity);
  return dT;
}

class NetworkSimbodyRun {
 public:
  NetworkSimbodyRun(const Network& net, NetworkSink& sink);
  NetworkRunReport run();

 private:
  State startState();
  std::unique_ptr<Integrator> makeRunIntegrator(const State& s0);
  // true when the step was redone (the integrator is back at the step's start)
  bool checkNewStep(Integrator& integ, Integrator::SuccessfulStepStatus status);
  bool slipAgainstMode(const State& s);
  void redoStep(Integrator& integ);
  void handleTrigger(Integrator& integ);
  bool windowIsLive() const;
  void resolveWindow(State& s);
  void settleSupports(State& s);
  void absorb(const WindowOutcome& out, int p);
  void sample(const State& s);
  double energy(const State& s) {
    ns_.system().realize(s, Stage::Velocity);
    return ns_.system().calcEnergy(s);
  }
  void noteDiscontinuity(double t) {
    if (storm_->note(t)) fail(t, storm_->why());
  }
  void fail(double t, const std::string& why);

  const Network& net_;
  NetworkSink& sink_;
  NetworkSystem ns_;
  const network::NetworkEquations& eq_;
  network::Layout lay_;
  Pending pending_;
  NetworkRunReport report_;
  SplitTimer timer_;  // the engine's time against the recording's
  std::vector<std::unique_ptr<ContactView>> views_;
  std::vector<EventResolver> resolvers_;
  std::optional<StormGuard> storm_;
  State* ev_s_ = nullptr;  // the state the resolvers act on
  double period_ = 1.0, sample_dt_ = 1.0, t_end_ = 0.0;
  long next_sample_ = 0;
  std::vector<double> y_;
  // the last accepted step's end (a redo starts there) and the redo's state
  State back_;
  int redo_depth_ = 0;
  double redo_until_ = -1.0;
  long steps_base_ = 0, evals_base_ = 0;
};

NetworkSimbodyRun::NetworkSimbodyRun(const Network& net, NetworkSink& sink)
    : net_(net), sink_(sink), ns_(net), eq_(ns_.equations()), lay_(eq_.layout()) {
  const ScaledParams sp = computeScaled(net.unionRig());
  period_ = 2 * Pi * sp.time_scale_s;
  t_end_ = net.sim.t_end_s;
  sample_dt_ = net.sim.sample_s > 0 ? net.sim.sample_s : period_ / 20;
  report_.engine = "simbody";
  report_.integrator =
      net.sim.integrator.empty() ? simbodyIntegratorNames().front() : net.sim.integrator;
  report_.fast_period_s = period_;
  report_.ticks.assign(net.numMetronomes(), 0);
  pending_.contacts.assign(lay_.platforms, 0);
  // witnesses: only what the network needs
  for (int j = 0; j < lay_.n; ++j)
    if (eq_.escapement(j).active())
      for (int side : {1, -1})
        ns_.system().addEventHandler(new TickHandler(ns_, j, side, pending_));
  for (int p = 0; p < lay_.platforms; ++p)
    if (ns_.contact(p)) ns_.system().addEventHandler(new ContactHandler(ns_, p, pending_));
  ns_.system().setDefaultTimeScale(sp.time_scale_s);
  ns_.system().realizeTopology();
  for (int p = 0; p < lay_.platforms; ++p)
    views_.push_back(std::make_unique<ContactView>(ns_, ev_s_, p, report_.events));
}

// The network's start, the resolvers armed by it, and every Coulomb contact's mode decided at
// rest in file order, the later ones held meanwhile (as the direct engine).
State NetworkSimbodyRun::startState() {
  State s0 = ns_.initialState();
  for (int p = 0; p < lay_.platforms; ++p) {
    const network::Block& b = eq_.block(p);
    std::vector<Escapement> esc;
    std::vector<double> th0;
    for (int j = b.first; j < b.first + b.count; ++j) {
      esc.push_back(eq_.escapement(j));
      th0.push_back(ns_.theta(s0, j));
    }
    resolvers_.emplace_back(esc, ns_.contact(p) ? b.friction : PlatformFriction{}, period_, th0);
  }
  for (int p = 0; p < lay_.platforms; ++p)
    if (ns_.contact(p)) ns_.contact(p)->setMode(s0, PlatformMode::Stuck);
  ev_s_ = &s0;
  for (int p = 0; p < lay_.platforms; ++p)
    if (ns_.contact(p)) resolvers_[p].settleAtStart(*views_[p]);
  ev_s_ = nullptr;
  ns_.system().realize(s0, Stage::Acceleration);
  return s0;
}

std::unique_ptr<Integrator> NetworkSimbodyRun::makeRunIntegrator(const State& s0) {
  std::unique_ptr<Integrator> integ = makeSimbodyIntegrator(report_.integrator, ns_.system());
  integ->setAccuracy(net_.sim.accuracy);
  integ->setFinalTime(t_end_);
  integ->setReturnEveryInternalStep(true);
  integ->setMaximumStepSize(kMaxStepPeriods * period_);
  integ->initialize(s0);
  return integ;
}

// Marks every slip running against its mode in s (pending_), and says whether there is one.
bool NetworkSimbodyRun::slipAgainstMode(const State& s) {
  bool against = false;
  for (int p = 0; p < lay_.platforms; ++p) {
    const CoulombContact* c = ns_.contact(p);
    if (!c || c->mode(s) == PlatformMode::Stuck) continue;
    if (static_cast<int>(c->mode(s)) * c->slipVelocity(s) < 0) {
      pending_.contacts[p] = 1;
      against = true;
    }
  }
  return against;
}

// Back to the last step's start, with steps kRedoShrink times smaller until past its end.
void NetworkSimbodyRun::redoStep(Integrator& integ) {
  const double t_end_of_step = integ.getAdvancedTime();
  pending_.clear();
  noteDiscontinuity(t_end_of_step);
  integ.setMaximumStepSize(
      std::max((t_end_of_step - back_.getTime()) / kRedoShrink, 1e-14 * period_));
  redo_until_ = t_end_of_step;
  ++redo_depth_;
  steps_base_ += integ.getNumStepsTaken();
  const long evals_before = integ.getNumRealizations();
  integ.initialize(back_);
  evals_base_ += evals_before - integ.getNumRealizations();
}

// A step just taken: a slip that reversed inside it (see kRedoShrink) redoes it, or at the
// finest steps is stopped at its end; its end re-arms the ticks whose pendulums are back inside.
bool NetworkSimbodyRun::checkNewStep(Integrator& integ, Integrator::SuccessfulStepStatus status) {
  State& adv = integ.updAdvancedState();
  for (int k = 0; k < adv.getNY(); ++k)
    if (!std::isfinite(adv.getY()[k])) {
      fail(adv.getTime(), "the state is not finite");
      return false;
    }
  const bool against = status != Integrator::ReachedEventTrigger && slipAgainstMode(adv);
  if (against && redo_depth_ < kMaxRedoDepth && adv.getTime() > back_.getTime()) {
    redoStep(integ);
    return true;
  }
  for (int p = 0; p < lay_.platforms; ++p) {
    const network::Block& b = eq_.block(p);
    for (int j = 0; j < b.count; ++j) resolvers_[p].rearm(j, ns_.theta(adv, b.first + j));
  }
  if (against) {
    // the samples inside the step first, from its interpolant (the stop restarts at its end)
    for (double ts = next_sample_ * sample_dt_; ts <= adv.getTime() && ts < t_end_;
         ts = next_sample_ * sample_dt_) {
      if (integ.getTime() < ts) integ.stepTo(ts, t_end_);
      sample(integ.getState());
      ++next_sample_;
    }
    State& end = integ.updAdvancedState();
    noteDiscontinuity(end.getTime());
    resolveWindow(end);
    integ.reinitialize(Stage::Model, false);
  }
  if (redo_depth_ > 0 && integ.getAdvancedTime() >= redo_until_) {
    redo_depth_ = 0;
    integ.setMaximumStepSize(kMaxStepPeriods * period_);
  }
  back_ = integ.getAdvancedState();
  return false;
}

bool NetworkSimbodyRun::windowIsLive() const {
  for (char c : pending_.contacts)
    if (c) return true;
  for (const auto& [j, side] : pending_.ticks) {
    int p = 0;
    while (j >= eq_.block(p).first + eq_.block(p).count) ++p;
    if (resolvers_[p].armed(j - eq_.block(p).first, side)) return true;
  }
  return false;
}

// Every triggered witness reports, then the window is resolved once on the window's end.
void NetworkSimbodyRun::handleTrigger(Integrator& integ) {
  State& adv = integ.updAdvancedState();
  HandleEventsOptions opts(integ.getAccuracyInUse());
  HandleEventsResults results;
  ns_.system().handleEvents(adv, Event::Cause::Triggered, integ.getTriggeredEvents(), opts,
                            results);
  if (!windowIsLive()) {
    pending_.clear();
    return;
  }
  noteDiscontinuity(adv.getTime());
  resolveWindow(adv);
  integ.reinitialize(Stage::Model, false);
  back_ = integ.getAdvancedState();
}

void NetworkSimbodyRun::absorb(const WindowOutcome& out, int p) {
  report_.ledger.escapement_in_J += out.escapement_in;
  report_.ledger.friction_out_J += out.friction_out;
  report_.stick_slip += out.stick_slip;
  report_.slip_reversals += out.slip_reversals;
  for (int j : out.ticked) ++report_.ticks[eq_.pendulum(eq_.block(p).first + j).rig_index];
}

// The direct engine's window: each platform's resolver in file order (a contact counts as
// reported when its witness has crossed: the stick margins judged on the window's state before
// any impulse, the slip velocities when the platform's turn comes), then the supports.
void NetworkSimbodyRun::resolveWindow(State& s) {
  ns_.system().realize(s, Stage::Acceleration);
  ev_s_ = &s;
  std::vector<double> margin(lay_.platforms, 1.0);
  for (int p = 0; p < lay_.platforms; ++p)
    if (ns_.contact(p) && ns_.contact(p)->mode(s) == PlatformMode::Stuck)
      margin[p] = ns_.contact(p)->witness(s);
  for (int p = 0; p < lay_.platforms; ++p) {
    const CoulombContact* c = ns_.contact(p);
    bool reported = false;
    if (c) {
      const PlatformMode m = c->mode(s);
      const double g =
          m == PlatformMode::Stuck ? margin[p] : static_cast<int>(m) * c->slipVelocity(s);
      reported = pending_.contacts[p] || g <= 0;
    }
    absorb(resolvers_[p].resolve(*views_[p], reported), p);
  }
  settleSupports(s);
  ++report_.events;
  ev_s_ = nullptr;
  pending_.clear();
  ns_.system().realize(s, Stage::Acceleration);
}

// Contacts the window's later changes left inconsistent (as the direct engine): stuck with a
// velocity (an impulse below), stuck beyond the bound (another contact's switch or tick changed
// the forces on it), or slipping against their mode.
void NetworkSimbodyRun::settleSupports(State& s) {
  for (int pass = 0; pass < kSettlePassesPerPlatform * lay_.platforms; ++pass) {
    bool changed = false;
    for (int p = 0; p < lay_.platforms; ++p) {
      const CoulombContact* c = ns_.contact(p);
      if (!c) continue;
      const double u = c->slipVelocity(s);
      const PlatformMode m = c->mode(s);
      bool off = static_cast<int>(m) * u <= 0;
      if (m == PlatformMode::Stuck) {
        ns_.system().realize(s, Stage::Acceleration);
        off = u != 0 || c->law().breaksFree(c->holdingForce(s));
      }
      if (!off) continue;
      absorb(resolvers_[p].settleAfterSupportImpulse(*views_[p]), p);
      changed = true;
    }
    if (!changed) return;
  }
}

void NetworkSimbodyRun::sample(const State& s) {
  RecordingScope rec(timer_);
  ns_.layoutState(s, y_);
  std::vector<PlatformMode> modes(lay_.platforms, PlatformMode::Stuck);
  for (int p = 0; p < lay_.platforms; ++p)
    if (ns_.contact(p)) modes[p] = ns_.contact(p)->mode(s);
  sink_.sample(s.getTime(), y_, modes);
}

void NetworkSimbodyRun::fail(double t, const std::string& why) {
  if (!report_.complete) return;
  report_.complete = false;
  report_.failure = "at t = " + std::to_string(t) + " s: " + why;
}

NetworkRunReport NetworkSimbodyRun::run() {
  timer_ = SplitTimer();
  storm_.emplace(period_);
  State s0 = startState();
  report_.ledger.initial_J = energy(s0);
  std::unique_ptr<Integrator> integ = makeRunIntegrator(s0);
  sample(integ->getState());
  next_sample_ = 1;
  double checked_until = integ->getAdvancedTime();
  back_ = integ->getAdvancedState();
  try {
    while (report_.complete && integ->getTime() < t_end_) {
      const double ts = next_sample_ * sample_dt_;
      if (ts < integ->getTime()) {  // taken already (a sample at the end of a step)
        ++next_sample_;
        continue;
      }
      const Integrator::SuccessfulStepStatus status = integ->stepTo(std::min(ts, t_end_), t_end_);
      if (integ->getAdvancedTime() > checked_until) {
        const bool redone = checkNewStep(*integ, status);
        checked_until = integ->getAdvancedTime();
        if (!report_.complete) break;
        if (redone) continue;
      }
      if (status == Integrator::ReachedEventTrigger) {
        handleTrigger(*integ);
      } else if (integ->getTime() == next_sample_ * sample_dt_ && integ->getTime() < t_end_) {
        sample(integ->getState());
        ++next_sample_;
      }
      if (integ->isSimulationOver()) break;
    }
  } catch (const std::exception& e) {
    fail(integ->getAdvancedTime(), e.what());
  }
  const State& fin = integ->getState();
  sample(fin);  // the last sample: the final state (grid samples stop short of t_end)
  report_.steps = steps_base_ + integ->getNumStepsTaken();
  report_.rhs_evals = evals_base_ + integ->getNumRealizations();
  report_.t_end = fin.getTime();
  ns_.layoutState(fin, report_.final_state);
  report_.ledger.final_J = energy(fin);
  report_.ledger.damping_out_J = ns_.dampingLoss(fin) + ns_.damperLoss(fin);
  report_.ledger.friction_out_J += ns_.frictionLoss(fin);
  report_.wall_seconds = timer_.wallSeconds();
  report_.engine_seconds = report_.wall_seconds - timer_.recordingSeconds(report_.wall_seconds);
  return report_;
}

}  // namespace

NetworkRunReport runNetworkSimbody(const Network& net, NetworkSink& sink) {
  return NetworkSimbodyRun(net, sink).run();
}

}  // namespace metrosync
