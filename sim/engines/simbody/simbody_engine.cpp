// The full model's run loop on Simbody. The pieces, top to bottom:
//   1. witnesses: thin TriggeredEventHandlers that only say "my witness crossed" (ticks: rising
//      theta_i -/+ theta_c; platform: falling mode*xdot while slipping, falling stick margin while
//      stuck). Simbody calls every handler whose witness crossed in the localization window, in
//      registration order, on the same state; so none of them acts.
//   2. one resolver acts on the whole window at once, in a fixed order: escapement impulses
//      first (all ticking pendulums together, through the unlocked mass matrix: dry friction
//      gives no impulse), then the platform's mode, decided from the resulting state. The result
//      does not depend on the order in which Simbody called the handlers.
//   3. a grazing guard: a step whose end points both lie inside +-theta_c (or both on one side of
//      xdot = 0) can still have crossed twice; the cubic Hermite through the step's end values
//      finds such steps and the step is redone with smaller steps.
//   4. recorders: trajectory rows and envelope samples by interpolation (the integrator is
//      never forced to stop at a sample), with samples on both sides of every event.
#include "sim/engines/simbody/simbody_engine.h"

#include <Simbody.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>

#include "models/simbody/metronome_system.h"
#include "sim/record/envelope_recorder.h"

namespace metrosync {

using namespace SimTK;

const std::vector<std::string>& simbodyIntegratorNames() {
  static const std::vector<std::string> names = {
      "rk-merson", "rk-feldberg", "rk3", "rk2", "cpodes", "verlet", "semi-explicit-euler2"};
  return names;
}

namespace {

std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const System& sys) {
  if (name == "rk-merson") return std::make_unique<RungeKuttaMersonIntegrator>(sys);
  if (name == "rk-feldberg") return std::make_unique<RungeKuttaFeldbergIntegrator>(sys);
  if (name == "rk3") return std::make_unique<RungeKutta3Integrator>(sys);
  if (name == "rk2") return std::make_unique<RungeKutta2Integrator>(sys);
  if (name == "cpodes")
    return std::make_unique<CPodesIntegrator>(sys, CPodes::Adams, CPodes::Functional);
  if (name == "verlet") return std::make_unique<VerletIntegrator>(sys);
  if (name == "semi-explicit-euler2") return std::make_unique<SemiExplicitEuler2Integrator>(sys);
  throw std::invalid_argument("unknown integrator '" + name + "'");
}

// What the witnesses report to the resolver within one localization window.
struct Pending {
  std::vector<bool> tick;  // (N x 1)
  bool platform = false;
  void clear() {
    std::fill(tick.begin(), tick.end(), false);
    platform = false;
  }
};

class TickWitness : public TriggeredEventHandler {
 public:
  TickWitness(const MetronomeSystem& ms, int i, int side, Pending& pending)
      : TriggeredEventHandler(Stage::Position), ms_(ms), i_(i), side_(side), pending_(pending) {
    getTriggerInfo().setTriggerOnRisingSignTransition(true);
    getTriggerInfo().setTriggerOnFallingSignTransition(false);
  }
  // side*theta - theta_c: rises through zero when the pendulum passes +-theta_c outwards
  Real getValue(const State& s) const override {
    return side_ * ms_.theta(s, i_) - ms_.rig().metronomes[i_].theta_c_rad;
  }
  void handleEvent(State&, Real, bool&) const override { pending_.tick[i_] = true; }

 private:
  const MetronomeSystem& ms_;
  int i_, side_;
  Pending& pending_;
};

class PlatformWitness : public TriggeredEventHandler {
 public:
  PlatformWitness(const MetronomeSystem& ms, Pending& pending)
      : TriggeredEventHandler(Stage::Acceleration), ms_(ms), pending_(pending) {
    getTriggerInfo().setTriggerOnRisingSignTransition(false);
    getTriggerInfo().setTriggerOnFallingSignTransition(true);
  }
  // slipping: mode*xdot (falls through zero when the platform stops);
  // stuck: bound - |holding force| (falls through zero when friction can no longer hold it)
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

class FullModelRun {
 public:
  FullModelRun(const Rig& rig, RunSink& sink)
      : rig_(rig),
        sp_(computeScaled(rig)),
        ms_(rig),
        sink_(sink),
        n_(ms_.numMetronomes()),
        env_(sp_.epsilon, activeMask(rig), sink) {
    pending_.tick.assign(n_, false);
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
      ms_.system().addEventHandler(new TickWitness(ms_, i, +1, pending_));
      ms_.system().addEventHandler(new TickWitness(ms_, i, -1, pending_));
    }
    if (ms_.coulomb()) ms_.system().addEventHandler(new PlatformWitness(ms_, pending_));
    ms_.system().setDefaultTimeScale(sp_.time_scale_s);
    ms_.system().realizeTopology();
  }

  RunReport run();

 private:
  static std::vector<bool> activeMask(const Rig& rig) {
    std::vector<bool> a;
    for (const auto& m : rig.metronomes) a.push_back(!m.locked);
    return a;
  }

  // --- event resolution -------------------------------------------------------------------
  bool tickDue(const State& s, int i) const {
    const double th = ms_.theta(s, i), w = ms_.thetadot(s, i);
    const double tc = rig_.metronomes[i].theta_c_rad;
    // re-check: outward through +-theta_c (the localization window ends just past the root)
    return std::abs(th) >= tc * (1 - 1e-9) && th * w > 0;
  }
  void decideAtRest(State& s, PlatformMode before);
  // (M^-1)_xx: the platform's velocity change per unit impulse on x (the platform unlocked)
  double platformMobility(const State& s) const {
    Vector f(s.getNU(), 0.0), du;
    ms_.slider().applyOneMobilityForce(s, 0, 1.0, f);
    ms_.matter().multiplyByMInv(s, f, du);
    return ms_.slider().getOneFromUPartition(s, 0, du);
  }
  // would friction alone stop a platform slipping at v within a millionth of a period?
  bool microSlip(const State& s, double v) const {
    const double decel = ms_.coulomb()->law().bound * platformMobility(s);
    return std::abs(v) < 1e-6 * period_ * decel;
  }
  void stopPlastically(State& s, double v) {
    Vector f(s.getNU(), 0.0), du;
    ms_.slider().applyOneMobilityForce(s, 0, -v / platformMobility(s), f);
    ms_.matter().multiplyByMInv(s, f, du);
    s.updU() += du;
    ms_.setXDot(s, 0.0);
    ms_.system().realize(s, Stage::Velocity);
  }
  Stage resolve(State& s);

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

  const Rig& rig_;
  ScaledParams sp_;
  MetronomeSystem ms_;
  RunSink& sink_;
  int n_;
  EnvelopeRecorder env_;
  Pending pending_;
  RunReport report_;
  double omega0_ = 1;
  double period_ = 1;  // fast period, seconds
  long rewinds_ = 0;
  bool debug_ = std::getenv("METROSYNC_DEBUG") != nullptr;
  std::vector<double> scratch_th_, scratch_w_;
};

void FullModelRun::decideAtRest(State& s, PlatformMode before) {
  const CoulombElement& c = *ms_.coulomb();
  const PlatformMode after = c.settleAtRest(ms_.system(), s);
  if (after != before) {
    ++report_.counts.stick_slip;
    eventRow(after == PlatformMode::Stuck ? "stick" : "slip", s);
  }
}

Stage FullModelRun::resolve(State& s) {
  Stage lowest = Stage::Infinity;
  ms_.system().realize(s, Stage::Velocity);
  const CoulombElement* coulomb = ms_.coulomb();

  // 1. escapement: every pendulum whose witness crossed and whose tick condition still holds
  std::vector<int> ticking;
  for (int i = 0; i < n_; ++i)
    if (pending_.tick[i] && tickDue(s, i)) ticking.push_back(i);
  if (!ticking.empty()) {
    const double e0 = energy(s);
    const bool was_stuck = coulomb && coulomb->mode(s) == PlatformMode::Stuck;
    if (was_stuck) {
      coulomb->slip(s, PlatformMode::SlipPositive);  // provisional: unlocks the slider
      ms_.system().realize(s, Stage::Position);
    }
    // generalized impulse +-J-bar on each ticking pin, through the unlocked mass matrix
    const SimbodyMatterSubsystem& matter = ms_.matter();
    Vector du_total(s.getNU(), 0.0);
    double dv_abs = 0.0;  // sum of the platform velocity jumps, for the cancellation test
    for (int i : ticking) {
      Vector impulse(s.getNU(), 0.0), du;
      const double side = ms_.theta(s, i) > 0 ? 1.0 : -1.0;
      ms_.pin(i).applyOneMobilityForce(s, 0, side * rig_.metronomes[i].impulse_Nms, impulse);
      matter.multiplyByMInv(s, impulse, du);
      du_total += du;
      if (ms_.hasPlatform()) dv_abs += std::abs(ms_.slider().getOneFromUPartition(s, 0, du));
      ++report_.counts.escapements[i];
    }
    s.updU() += du_total;
    ms_.system().realize(s, Stage::Velocity);
    lowest = Stage::Velocity;
    // the escapement's work: the kinetic energy jump of the impulses alone (what the platform
    // does next is booked by its own rule)
    report_.ledger.escapement_in_J += energy(s) - e0;
    if (coulomb) {
      const double v = ms_.xdot(s);
      if (std::abs(v) <= 1e-9 * dv_abs) {
        // the impulses cancel on the platform (e.g. identical metronomes in exact antiphase);
        // xdot (rounding-sized) is set to 0
        const double e_before = energy(s);
        decideAtRest(s, was_stuck ? PlatformMode::Stuck : coulomb->mode(s));
        report_.ledger.friction_out_J += e_before - energy(s);
      } else if (microSlip(s, v)) {
        // friction stops the platform within a negligible time (a huge mu): the limit of that
        // slip is a plastic stop, an impulse on x alone that brings xdot to zero; the kinetic
        // energy it removes is friction's. It is counted and recorded as the direct engine
        // (which integrates that slip) counts it: a slip, unless one was under way in that
        // direction, then its stop as an event of its own
        const PlatformMode m = v > 0 ? PlatformMode::SlipPositive : PlatformMode::SlipNegative;
        const PlatformMode before = was_stuck ? PlatformMode::Stuck : coulomb->mode(s);
        if (m != before) {
          ++report_.counts.stick_slip;
          eventRow("slip", s);
        }
        const double e_before = energy(s);
        stopPlastically(s, v);
        report_.ledger.friction_out_J += e_before - energy(s);
        ++report_.counts.events;
        decideAtRest(s, m);
      } else {
        const PlatformMode m = v > 0 ? PlatformMode::SlipPositive : PlatformMode::SlipNegative;
        const PlatformMode before = was_stuck ? PlatformMode::Stuck : coulomb->mode(s);
        coulomb->slip(s, m);
        if (m != before) {
          ++report_.counts.stick_slip;
          eventRow("slip", s);
        }
      }
      lowest = Stage::Model;
    }
    eventRow("tick", s);
  }

  // 2. the platform: its switching rule, on the current state
  if (coulomb && (pending_.platform || !ticking.empty())) {
    const PlatformMode before = coulomb->mode(s);
    const double e0 = energy(s);
    const PlatformMode after = coulomb->resolveSwitch(ms_.system(), s);
    if (after != before) {
      ++report_.counts.stick_slip;
      eventRow(after == PlatformMode::Stuck ? "stick" : "slip", s);
      // a stop sets xdot (~1e-12 past zero at the window's end) to exactly 0: book that
      // kinetic energy as friction loss
      report_.ledger.friction_out_J += e0 - energy(s);
      lowest = Stage::Model;
    }
  }
  pending_.clear();
  if (lowest < Stage::Infinity) ms_.system().realize(s, Stage::Acceleration);
  return lowest;
}

void FullModelRun::recordTrajectory(const State& s, double t) {
  std::vector<double> row = makeRow(s, t);
  sink_.trajectoryRow(row);
  report_.final_trajectory_row = std::move(row);
}

void FullModelRun::eventRow(const char* kind, const State& s) {
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
  const auto wall0 = std::chrono::steady_clock::now();
  const double t_end = rig_.sim.t_end_s;
  const double period = 2 * Pi / omega0_;
  const double traj_dt = rig_.sim.sample_s > 0 ? rig_.sim.sample_s : period / 20;
  const double env_dt = period / 64;

  State s0 = ms_.initialState();
  if (const CoulombElement* c = ms_.coulomb()) {
    const double v = ms_.xdot(s0);
    if (v == 0)
      decideAtRest(s0, PlatformMode::Stuck);
    else
      c->slip(s0, v > 0 ? PlatformMode::SlipPositive : PlatformMode::SlipNegative);
    report_.counts.stick_slip = 0;  // the start is not a switch
  }
  ms_.system().realize(s0, Stage::Acceleration);
  report_.ledger.initial_J = energy(s0);

  std::unique_ptr<Integrator> integ = makeIntegrator(report_.integrator, ms_.system());
  integ->setAccuracy(rig_.sim.accuracy);
  integ->setFinalTime(t_end);
  integ->setReturnEveryInternalStep(true);
  // witnesses that cross twice in one step are missed; the pendulums normally keep steps far
  // below this, but a stuck platform with dead pendulums would not
  integ->setMaximumStepSize(period / 8);
  integ->initialize(s0);

  long k_traj = 0, k_env = 0;
  recordTrajectory(integ->getState(), 0.0);
  recordEnvelope(integ->getState(), 0.0);
  k_traj = k_env = 1;

  StepEnd prev, cur;
  captureStepEnd(integ->getAdvancedState(), prev);
  double checked_until = integ->getAdvancedTime();
  long steps_base = 0, evals_base = 0;
  double guard_until = -1;  // while redoing a grazing step: time until which hmax is reduced
  int guard_depth = 0;
  double hmax = Infinity;
  // event storm (Zeno): too many discontinuities (events, forced stops, redone steps) within a
  // millionth of a fast period
  long events_in_burst = 0;
  double burst_start = -Infinity;
  const long kMaxBurst = 1000;
  auto stormCheck = [&](double t) {
    if (t - burst_start > 1e-6 * period) {
      burst_start = t;
      events_in_burst = 0;
    }
    if (++events_in_burst > kMaxBurst) {
      std::ostringstream os;
      os << "event storm: more than " << kMaxBurst << " events within " << 1e-6 * period
         << " s (a millionth of a fast period)";
      fail(t, os.str());
    }
  };

  auto nextReport = [&]() {
    return std::min(
        {static_cast<double>(k_traj) * traj_dt, static_cast<double>(k_env) * env_dt, t_end});
  };

  try {
    while (true) {
      const double t_now = integ->getTime();
      // reports due at or before the current time (possible right after an event)
      while (nextReport() <= t_now && nextReport() < t_end) {
        const double tr = nextReport();
        if (static_cast<double>(k_traj) * traj_dt <= tr)
          recordTrajectory(integ->getState(), tr), ++k_traj;
        if (static_cast<double>(k_env) * env_dt <= tr)
          recordEnvelope(integ->getState(), tr), ++k_env;
      }
      if (t_now >= t_end) break;

      const Integrator::SuccessfulStepStatus status = integ->stepTo(nextReport(), t_end);

      // a new step has been taken: check it before anything from it is recorded
      if (integ->getAdvancedTime() > checked_until) {
        const State& adv = integ->getAdvancedState();
        if (!allFinite(adv.getY())) {
          fail(adv.getTime(), "non-finite state");
          break;
        }
        captureStepEnd(adv, cur);
        const PlatformMode mode = ms_.coulomb() ? ms_.coulomb()->mode(adv) : PlatformMode::Stuck;
        const bool event_step = status == Integrator::ReachedEventTrigger;
        if (guard_depth < 5 && cur.t - prev.t > 1e-12 * period &&
            grazingMissed(prev, cur, mode, event_step)) {
          // redo the step from its start with steps 8 times smaller
          const double h = cur.t - prev.t;
          steps_base += integ->getNumStepsTaken();
          const long evals_before = integ->getNumRealizations();
          State back = adv;
          back.setTime(prev.t);
          back.updY() = prev.y;
          ms_.system().realize(back, Stage::Acceleration);
          hmax = std::max(h / 8, 1e-14 * period);
          integ->setMaximumStepSize(hmax);
          guard_until = cur.t;
          ++guard_depth;
          ++rewinds_;
          stormCheck(cur.t);
          if (!report_.complete) break;
          if (debug_)
            std::fprintf(stderr, "rewind %.9g..%.9g depth %d\n", prev.t, cur.t, guard_depth);
          integ->initialize(back);
          evals_base += evals_before - integ->getNumRealizations();
          checked_until = prev.t;
          continue;
        }
        if (ms_.coulomb() && mode != PlatformMode::Stuck && static_cast<int>(mode) * cur.v < 0 &&
            !event_step) {
          // still inconsistent at the finest step: the slip ended inside this step; stop now
          if (debug_) std::fprintf(stderr, "forced stop at %.9g v %g\n", cur.t, cur.v);
          State& st = integ->updAdvancedState();
          stormCheck(cur.t);
          pending_.platform = true;
          const Stage lowest = resolve(st);
          integ->reinitialize(lowest < Stage::Infinity ? lowest : Stage::Report, false);
          captureStepEnd(integ->getAdvancedState(), cur);
        }
        if (guard_depth > 0 && cur.t >= guard_until) {
          guard_depth = 0;
          hmax = period / 8;
          integ->setMaximumStepSize(hmax);
        }
        prev = cur;
        checked_until = cur.t;
      }

      switch (status) {
        case Integrator::ReachedReportTime:
        case Integrator::ReachedScheduledEvent:
        case Integrator::EndOfSimulation: {
          const double t = integ->getTime();
          if (static_cast<double>(k_traj) * traj_dt <= t && t < t_end) {
            recordTrajectory(integ->getState(), t);
            ++k_traj;
          }
          if (static_cast<double>(k_env) * env_dt <= t && t < t_end) {
            recordEnvelope(integ->getState(), t);
            ++k_env;
          }
          break;
        }
        case Integrator::ReachedEventTrigger: {
          ++report_.counts.events;
          // the last state before the event (interpolated at the window's low end)
          recordEnvelope(integ->getState(), integ->getTime());
          State& adv = integ->updAdvancedState();
          // let every triggered witness report, then act once on the whole window
          HandleEventsOptions opts(integ->getAccuracyInUse());
          HandleEventsResults results;
          ms_.system().handleEvents(adv, Event::Cause::Triggered, integ->getTriggeredEvents(), opts,
                                    results);
          if (debug_)
            std::fprintf(stderr, "event at %.9g mode %d\n", adv.getTime(),
                         ms_.coulomb() ? (int)ms_.coulomb()->mode(adv) : 9);
          const Stage lowest = resolve(adv);
          integ->reinitialize(lowest < Stage::Infinity ? lowest : Stage::Report, false);
          recordEnvelope(integ->getAdvancedState(), integ->getAdvancedTime());
          captureStepEnd(integ->getAdvancedState(), prev);
          checked_until = integ->getAdvancedTime();
          stormCheck(adv.getTime());
          break;
        }
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

  report_.counts.steps = steps_base + integ->getNumStepsTaken();
  report_.counts.rhs_evals = evals_base + integ->getNumRealizations();
  report_.ledger.final_J = energy(fin);
  report_.ledger.damping_out_J = ms_.meter().dampingLoss(fin);
  report_.ledger.friction_out_J += ms_.meter().frictionLoss(fin);
  report_.has_ledger = true;
  if (std::getenv("METROSYNC_DEBUG"))
    std::fprintf(stderr, "debug: rewinds %ld steps %d attempts %d realizations %d\n", rewinds_,
                 integ->getNumStepsTaken(), integ->getNumStepsAttempted(),
                 integ->getNumRealizations());
  report_.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return report_;
}

}  // namespace

RunReport runFullModel(const Rig& rig, RunSink& sink) {
  FullModelRun run(rig, sink);
  return run.run();
}

}  // namespace metrosync
