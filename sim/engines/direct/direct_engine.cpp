// The direct engine's run loop. Top to bottom:
//   1. witnesses with an explicit direction, each rising through zero at its event:
//        tick (i, side):  side * theta_i - theta_c,i          (passes +-theta_c outwards)
//        slipping:        -mode * xdot                         (the slip's velocity reaches 0)
//        stuck:           |H| - bound                          (friction can no longer hold it)
//   2. detection on each kept step: a sign change between the step's ends, or a hidden double
//      crossing (grazing) found at the extreme of the witness inside the step (the root of its
//      rate on the dense output); then each crossing is bracketed by Illinois on the dense output
//      to a few ulps. The event is placed at the earliest bracket's upper end, and every witness
//      that has crossed there belongs to the same window.
//   3. one resolver for the window, in Simbody's order: escapement impulses first (all ticking
//      pendulums together, through the full mass matrix with the platform free), then the
//      platform's Coulomb rule on the resulting state.
//   4. recorders: trajectory rows and envelope samples from the dense output (the integrator is
//      never stopped at a sample), samples on both sides of every event, the energy ledger from
//      two quadrature states.
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

#include "models/minimal_equations.h"
#include "models/scaling.h"
#include "sim/ode/rk_stepper.h"
#include "sim/ode/root_find.h"
#include "sim/record/envelope_recorder.h"

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

constexpr double kTwoPi = 6.283185307179586;
// Simbody's tickDue(): a tick needs |theta| >= theta_c (1 - 1e-9) and an outward rate.
constexpr double kTickSlack = 1e-9;
// Simbody's cancellation rule: ticks whose platform impulses cancel to this fraction leave the
// platform at rest.
constexpr double kCancelTol = 1e-9;

class Dynamics : public OdeRhs {
 public:
  explicit Dynamics(const MetronomeEquations& eq) : eq_(eq) {}
  void eval(const double* y, double* dy) override { eq_.rhs(y, mode, dy); }
  PlatformMode mode = PlatformMode::Stuck;

 private:
  const MetronomeEquations& eq_;
};

enum class WitnessKind { Tick, Platform };

struct Witness {
  WitnessKind kind;
  int pendulum = -1;  // Tick: index among the swinging pendulums
  int side = 0;       // Tick: +1 or -1
};

// A crossing found in the current step: the bracket of its root in th (fraction of the step).
struct Crossing {
  int witness = 0;
  Bracket th;
  bool forced = false;  // a slip that could not get going: stopped a sixteenth into the step
};

class DirectRun {
 public:
  DirectRun(const Rig& rig, RunSink& sink, const DirectOptions& opt);
  RunReport run();

 private:
  // --- witnesses --------------------------------------------------------------------------
  double witnessAt(const Witness& w, double th);
  std::optional<Crossing> detect(int index);
  std::optional<Crossing> detectComponent(int index, int k, double sign, double offset,
                                          bool allow_forced);
  std::optional<Crossing> detectMargin(int index);
  std::optional<Crossing> detectSlipFromRest(int index, int k, double sign, double g1);
  // the stuck platform's witness |H| - bound (minus CoulombLaw's stick margin) and its rate
  double excessPush(const double* y) const {
    return std::abs(eq_.holdingForce(y)) - eq_.coulomb().bound;
  }
  double excessPushRate(const double* y) const {
    const double h = eq_.holdingForce(y);
    return (h >= 0 ? 1.0 : -1.0) * eq_.holdingForceRate(y);
  }

  // --- event resolution -------------------------------------------------------------------
  bool tickDue(const double* y, int j) const {
    const double th = y[lay_.theta(j)], w = y[lay_.omega(j)];
    return std::abs(th) >= eq_.pendulum(j).theta_c * (1 - kTickSlack) && th * w > 0;
  }
  bool mustBreakFree(double holding) const {
    const CoulombLaw& law = eq_.coulomb();
    // the law's rule (shared with the Simbody engine): the push has reached the bound
    return law.breaksFree(holding);
  }
  PlatformMode settleAtRest(double* y);
  PlatformMode resolveSwitch(double* y);
  void resolve(double* y, double t, const std::vector<int>& ticks_due, bool platform);
  void setMode(PlatformMode m) { dyn_.mode = m; }
  PlatformMode mode() const { return dyn_.mode; }

  // --- recording --------------------------------------------------------------------------
  const std::vector<double>& makeRow(const double* y, double t);  // in row_
  void recordTrajectory(const double* y, double t);
  void recordEnvelope(const double* y, double t);
  void eventRow(const char* kind, const double* y, double t) {
    sink_.eventRow(kind, makeRow(y, t));
  }
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

  const Rig& rig_;
  DirectOptions opt_;
  ScaledParams sp_;
  MetronomeEquations eq_;
  StateLayout lay_;
  RunSink& sink_;
  int n_rig_;
  EnvelopeRecorder env_;
  Dynamics dyn_;
  const RkTableau& tab_;
  RkStepper stepper_;
  RunReport report_;
  double omega0_ = 1.0, period_ = 1.0;
  std::vector<Witness> witnesses_;
  std::vector<Crossing> found_;
  std::vector<double> ya_, yb_;  // scratch states (dim): the event's, the witnesses'
  std::vector<double> env_th_, env_w_;
  std::vector<double> row_;         // the trajectory row being written
  double friction_settle_J_ = 0.0;  // kinetic energy removed by setting xdot to 0
  bool debug_ = std::getenv("METROSYNC_DEBUG") != nullptr;
  // output schedule
  double traj_dt_ = 0.0, env_dt_ = 0.0, t_end_ = 0.0;
  long k_traj_ = 1, k_env_ = 1;
};

DirectRun::DirectRun(const Rig& rig, RunSink& sink, const DirectOptions& opt)
    : rig_(rig),
      opt_(opt),
      sp_(computeScaled(rig)),
      eq_(rig),
      lay_(eq_.layout()),
      sink_(sink),
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
  for (int j = 0; j < lay_.n; ++j) {
    if (!(eq_.pendulum(j).impulse > 0)) continue;
    witnesses_.push_back({WitnessKind::Tick, j, +1});
    witnesses_.push_back({WitnessKind::Tick, j, -1});
  }
  if (eq_.law() == FrictionLaw::Coulomb) witnesses_.push_back({WitnessKind::Platform, -1, 0});
  ya_.resize(lay_.dim());
  yb_.resize(lay_.dim());
  env_th_.resize(n_rig_, 0.0);
  env_w_.resize(n_rig_, 0.0);

  // error control in the scaled variables' units (s2.1): angles in units of sqrt(eps), the
  // platform in units of I1 eps^{3/2} / (m1 L1), time in 1/omega0; the ledger's quadratures are
  // not controlled (nothing depends on them)
  const double acc = rig.sim.accuracy;
  std::vector<double> atol(lay_.dim(), -1.0);
  atol[StateLayout::kX] = acc * sp_.x_scale_m;
  atol[StateLayout::kV] = acc * sp_.x_scale_m * omega0_;
  for (int j = 0; j < lay_.n; ++j) {
    atol[lay_.theta(j)] = acc * sp_.angle_scale;
    atol[lay_.omega(j)] = acc * sp_.angle_scale * omega0_;
  }
  stepper_.setTolerances(acc, atol);
}

// --- witnesses ------------------------------------------------------------------------------

double DirectRun::witnessAt(const Witness& w, double th) {
  if (w.kind == WitnessKind::Tick)
    return w.side * stepper_.component(lay_.theta(w.pendulum), th) -
           eq_.pendulum(w.pendulum).theta_c;
  if (mode() == PlatformMode::Stuck) {
    stepper_.interpolate(th, yb_.data());
    return excessPush(yb_.data());
  }
  return -static_cast<int>(mode()) * stepper_.component(StateLayout::kV, th);
}

std::optional<Crossing> DirectRun::detect(int index) {
  const Witness& w = witnesses_[index];
  if (w.kind == WitnessKind::Tick)
    return detectComponent(index, lay_.theta(w.pendulum), w.side, eq_.pendulum(w.pendulum).theta_c,
                           false);
  if (mode() == PlatformMode::Stuck) return detectMargin(index);
  return detectComponent(index, StateLayout::kV, -static_cast<int>(mode()), 0.0, true);
}

// g(th) = sign * y_k(th) - offset on the dense output, rising through zero.
std::optional<Crossing> DirectRun::detectComponent(int index, int k, double sign, double offset,
                                                   bool allow_forced) {
  const double g0 = sign * stepper_.y()[k] - offset;
  const double g1 = sign * stepper_.y1()[k] - offset;
  auto g = [&](double th) { return sign * stepper_.component(k, th) - offset; };
  auto rate = [&](double th) { return sign * stepper_.componentRate(k, th); };
  if (g0 < 0) {
    if (g1 >= 0) return Crossing{index, {0.0, 1.0}};
    // both ends below: a maximum inside the step may still reach zero (grazing); the rates at
    // the ends are f(y0), f(y1), inside they are the interpolant's
    const double d0 = sign * stepper_.f()[k], d1 = sign * stepper_.f1()[k];
    if (!(d0 > 0 && d1 < 0)) return std::nullopt;
    auto falling = [&](double th) { return -rate(th); };
    const Bracket top = illinois(falling, 0.0, -d0, 1.0, -d1);
    const double ga = g(top.lo), gb = g(top.hi);
    if (ga >= 0) return Crossing{index, {0.0, top.lo}};
    if (gb >= 0) return Crossing{index, {0.0, top.hi}};
    return std::nullopt;
  }
  // at or above zero at the start: a rising crossing needs a dip below zero first
  if (g0 == 0 && g1 == 0) return std::nullopt;
  if (allow_forced && g0 == 0) return detectSlipFromRest(index, k, sign, g1);
  const double d0 = sign * stepper_.f()[k], d1 = sign * stepper_.f1()[k];
  if (d0 < 0 && d1 > 0) {
    const Bracket bottom = illinois(rate, 0.0, d0, 1.0, d1);
    const double ga = g(bottom.lo), gb = g(bottom.hi);
    const double th_min = ga < gb ? bottom.lo : bottom.hi;
    if (std::min(ga, gb) < 0) {
      if (g1 >= 0) return Crossing{index, {th_min, 1.0}};
      return std::nullopt;  // went below and stayed there
    }
  }
  return std::nullopt;
}

// The first step of a slip that starts from rest (xdot = 0 exactly, so g0 = 0). The slip can start
// at a tangency of the stick margin, with an acceleration of rounding size at t0: the sign of the
// rate there says nothing, so the dip of g below zero (the slip under way) is looked for on the
// interpolant itself, and its end is the stop.
std::optional<Crossing> DirectRun::detectSlipFromRest(int index, int k, double sign, double g1) {
  if (g1 <= 0) return std::nullopt;  // still slipping the right way (or not at all) at the end
  auto g = [&](double th) { return sign * stepper_.component(k, th); };
  constexpr int kSamples = 16;
  double th_prev = 0.0;
  bool dipped = false;
  for (int s = 1; s <= kSamples; ++s) {
    const double th = static_cast<double>(s) / kSamples;
    const double v = s == kSamples ? g1 : g(th);
    if (v < 0) dipped = true;
    if (dipped && v >= 0) return Crossing{index, {th_prev, th}};
    th_prev = th;
  }
  // no sample below zero: the whole dip (if any) lies before the first sample
  const double th1 = 1.0 / kSamples;
  double a = 0.0, b = th1;
  constexpr double kGolden = 0.6180339887498949;
  double x1 = b - kGolden * (b - a), x2 = a + kGolden * (b - a);
  double f1 = g(x1), f2 = g(x2);
  for (int it = 0; it < 60; ++it) {
    if (f1 < f2) {
      b = x2, x2 = x1, f2 = f1;
      x1 = b - kGolden * (b - a), f1 = g(x1);
    } else {
      a = x1, x1 = x2, f1 = f2;
      x2 = a + kGolden * (b - a), f2 = g(x2);
    }
  }
  const double th_min = f1 < f2 ? x1 : x2;
  if (std::min(f1, f2) < 0) return Crossing{index, {th_min, th1}};
  // the slip could not get going at all (a start at a tangency that rounding put on the wrong
  // side): stop it at the first sample, where the margin has opened again
  return Crossing{index, {th1, th1}, true};
}

// |H| - bound while stuck: H is a function of the whole state, its rate known in closed form.
std::optional<Crossing> DirectRun::detectMargin(int index) {
  const double g0 = excessPush(stepper_.y()), g1 = excessPush(stepper_.y1());
  if (g0 >= 0) return std::nullopt;  // cannot happen: a platform stays stuck only below the bound
  if (g1 >= 0) return Crossing{index, {0.0, 1.0}};
  const double d0 = excessPushRate(stepper_.y()), d1 = excessPushRate(stepper_.y1());
  if (!(d0 > 0 && d1 < 0)) return std::nullopt;
  auto falling = [&](double th) {
    stepper_.interpolate(th, yb_.data());
    return -excessPushRate(yb_.data());
  };
  const Bracket top = illinois(falling, 0.0, -d0, 1.0, -d1);
  for (double th : {top.lo, top.hi}) {
    stepper_.interpolate(th, yb_.data());
    if (excessPush(yb_.data()) >= 0) return Crossing{index, {0.0, th}};
  }
  return std::nullopt;
}

// --- event resolution -----------------------------------------------------------------------

PlatformMode DirectRun::settleAtRest(double* y) {
  y[StateLayout::kV] = 0.0;
  const double h = eq_.holdingForce(y);
  const PlatformMode m = !mustBreakFree(h)
                             ? PlatformMode::Stuck
                             : (h > 0 ? PlatformMode::SlipNegative : PlatformMode::SlipPositive);
  setMode(m);
  return m;
}

PlatformMode DirectRun::resolveSwitch(double* y) {
  const PlatformMode m = mode();
  if (m == PlatformMode::Stuck) {
    const double h = eq_.holdingForce(y);
    if (!mustBreakFree(h)) return m;
    const PlatformMode to = h > 0 ? PlatformMode::SlipNegative : PlatformMode::SlipPositive;
    setMode(to);
    return to;
  }
  if (static_cast<int>(m) * y[StateLayout::kV] > 0) return m;
  return settleAtRest(y);
}

void DirectRun::resolve(double* y, double t, const std::vector<int>& ticks_due, bool platform) {
  const bool coulomb = eq_.law() == FrictionLaw::Coulomb;
  // 1. escapement: all ticking pendulums at once
  if (!ticks_due.empty()) {
    const bool was_stuck = coulomb && mode() == PlatformMode::Stuck;
    std::vector<std::pair<int, int>> ticks;
    for (int j : ticks_due) {
      ticks.emplace_back(j, y[lay_.theta(j)] > 0 ? 1 : -1);
      ++report_.counts.escapements[eq_.pendulum(j).rig_index];
    }
    const TickImpulse imp = eq_.applyTicks(y, ticks);
    double energy_in = imp.dT;  // the escapement's work (Simbody's ledger: E after - E before)
    if (coulomb) {
      const PlatformMode before = was_stuck ? PlatformMode::Stuck : mode();
      const double v = y[StateLayout::kV];
      if (std::abs(v) <= kCancelTol * imp.dv_abs) {
        // the impulses cancel on the platform (identical metronomes in exact antiphase)
        energy_in -= eq_.platformKineticEnergy(y);
        const PlatformMode after = settleAtRest(y);
        if (after != before) {
          ++report_.counts.stick_slip;
          eventRow(after == PlatformMode::Stuck ? "stick" : "slip", y, t);
        }
      } else {
        const PlatformMode m = v > 0 ? PlatformMode::SlipPositive : PlatformMode::SlipNegative;
        setMode(m);
        if (m != before) {
          ++report_.counts.stick_slip;
          eventRow("slip", y, t);
        }
      }
    }
    report_.ledger.escapement_in_J += energy_in;
    eventRow("tick", y, t);
  }
  // 2. the platform's rule on the resulting state
  if (coulomb && (platform || !ticks_due.empty())) {
    const PlatformMode before = mode();
    // a stop sets xdot (a rounding error past zero) to exactly 0: friction took that energy
    const double removed = before == PlatformMode::Stuck ? 0.0 : eq_.platformKineticEnergy(y);
    const PlatformMode after = resolveSwitch(y);
    if (after != before) {
      ++report_.counts.stick_slip;
      eventRow(after == PlatformMode::Stuck ? "stick" : "slip", y, t);
      if (y[StateLayout::kV] == 0.0) friction_settle_J_ += removed;
    }
  }
}

// --- recording ------------------------------------------------------------------------------

const std::vector<double>& DirectRun::makeRow(const double* y, double t) {
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
  if (eq_.law() == FrictionLaw::Coulomb) {
    row.push_back(static_cast<int>(mode()));
  } else {
    const double v = y[StateLayout::kV];
    row.push_back(v > 0 ? 1 : (v < 0 ? -1 : 0));
  }
  return row;
}

void DirectRun::recordTrajectory(const double* y, double t) {
  sink_.trajectoryRow(makeRow(y, t));
}

void DirectRun::recordEnvelope(const double* y, double t) {
  int j = 0;
  for (int i = 0; i < n_rig_; ++i) {
    if (rig_.metronomes[i].locked) continue;
    env_th_[i] = y[lay_.theta(j)] / sp_.angle_scale;
    env_w_[i] = y[lay_.omega(j)] / (sp_.angle_scale * omega0_);
    ++j;
  }
  env_.sample(t * omega0_, env_th_.data(), env_w_.data());
}

// Samples due in the current step before t_limit (or at it, if inclusive), from the dense output.
void DirectRun::emitSamplesBefore(double t_limit, bool inclusive) {
  const double t0 = stepper_.t(), h = stepper_.h();
  auto due = [&](double ts) {
    return ts < t_end_ && (ts < t_limit || (inclusive && ts == t_limit));
  };
  while (true) {
    const double tt = static_cast<double>(k_traj_) * traj_dt_;
    const double te = static_cast<double>(k_env_) * env_dt_;
    const double ts = std::min(tt, te);
    if (!due(ts)) break;
    const double th = std::clamp((ts - t0) / h, 0.0, 1.0);
    stepper_.interpolate(th, ya_.data());
    if (tt <= ts) {
      recordTrajectory(ya_.data(), ts);
      ++k_traj_;
    }
    if (te <= ts) {
      recordEnvelope(ya_.data(), ts);
      ++k_env_;
    }
  }
}

// --- the run --------------------------------------------------------------------------------

RunReport DirectRun::run() {
  const auto wall0 = std::chrono::steady_clock::now();
  t_end_ = rig_.sim.t_end_s;
  traj_dt_ = rig_.sim.sample_s > 0 ? rig_.sim.sample_s : period_ / 20;
  env_dt_ = period_ / 64;

  // the start: the rig's state, the platform's mode decided at rest
  std::vector<double> y(lay_.dim(), 0.0);
  if (eq_.hasPlatform()) {
    y[StateLayout::kX] = rig_.platform.start_x_m;
    y[StateLayout::kV] = rig_.platform.start_v_m_s;
  }
  for (int j = 0; j < lay_.n; ++j) {
    const MetronomeSpec& m = rig_.metronomes[eq_.pendulum(j).rig_index];
    y[lay_.theta(j)] = m.start_angle_rad;
    y[lay_.omega(j)] = m.start_rate_rad_s;
  }
  if (eq_.law() == FrictionLaw::Coulomb) {
    const double v = y[StateLayout::kV];
    if (v == 0) {
      setMode(PlatformMode::Stuck);
      if (settleAtRest(y.data()) != PlatformMode::Stuck) eventRow("slip", y.data(), 0.0);
    } else {
      setMode(v > 0 ? PlatformMode::SlipPositive : PlatformMode::SlipNegative);
    }
  }
  report_.ledger.initial_J = eq_.energy(y.data());

  // the largest step: a fraction of the fastest oscillation (pendulums, platform spring), so that
  // a step holds at most one extreme of any witness
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
  const double h_max = fastest / 10;

  stepper_.restart(0.0, y.data());
  double t_fin = 0.0;
  std::vector<double> y_fin = y;
  try {
    recordTrajectory(y.data(), 0.0);
    recordEnvelope(y.data(), 0.0);

    double h = std::min(h_max, 0.5 * period_ * std::pow(rig_.sim.accuracy, 1.0 / (tab_.order + 1)));
    long burst = 0;
    double burst_start = 0.0;
    int nonfinite = 0;
    std::vector<int> ticks_due;
    const double storm_window = opt_.storm_window * period_;

    while (stepper_.t() < t_end_) {
      const double t0 = stepper_.t();
      const bool last = t0 + h >= t_end_ * (1 - 4 * std::numeric_limits<double>::epsilon());
      const double step = last ? t_end_ - t0 : h;
      const double min_step =
          std::max(1e-14 * period_, 16 * std::numeric_limits<double>::epsilon() * t0);
      if (!(step > min_step) && !last) {
        fail(t0, "step size underflow (h = " + std::to_string(step) + " s)");
        break;
      }
      const double err = stepper_.attempt(step);
      if (!(err <= 1.0)) {
        // a step that produced a NaN or an infinity is redone 4 times smaller, a few times; a
        // state that is not finite itself fails at once
        if (!std::isfinite(err) &&
            (++nonfinite > 50 || !std::all_of(stepper_.y(), stepper_.y() + lay_.mechanical(),
                                              [](double v) { return std::isfinite(v); }))) {
          fail(t0, "non-finite state");
          break;
        }
        h = std::isfinite(err) ? stepper_.nextStepSize(step, err, false) : 0.25 * step;
        continue;
      }
      nonfinite = 0;
      ++report_.counts.steps;
      const double h_next = std::min(h_max, stepper_.nextStepSize(step, err, true));
      const double t1 = last ? t_end_ : stepper_.t1();

      // events in this step
      found_.clear();
      for (int w = 0; w < static_cast<int>(witnesses_.size()); ++w)
        if (auto c = detect(w)) found_.push_back(*c);
      if (found_.empty()) {
        emitSamplesBefore(t1, true);
        stepper_.advance();
        if (last) break;
        h = h_next;
        continue;
      }

      // bracket the crossings to a few ulps, earliest first; the window ends at the earliest
      // upper end (a crossing that starts after it cannot be earlier and needs no bracketing)
      std::sort(found_.begin(), found_.end(),
                [](const Crossing& a, const Crossing& b) { return a.th.lo < b.th.lo; });
      double th_e = 2.0;
      for (Crossing& c : found_) {
        if (c.th.lo >= th_e) break;
        if (!c.forced && c.th.hi > c.th.lo) {
          const Witness& w = witnesses_[c.witness];
          auto g = [&](double th) { return witnessAt(w, th); };
          c.th = illinois(g, c.th.lo, g(c.th.lo), c.th.hi, g(c.th.hi));
        }
        th_e = std::min(th_e, c.th.hi);
      }
      const double t_e = th_e >= 1.0 ? t1 : t0 + th_e * step;
      emitSamplesBefore(t_e, false);
      stepper_.interpolate(th_e, ya_.data());
      // every witness that has crossed by the window's end belongs to it
      ticks_due.clear();
      bool platform = false;
      for (const Crossing& c : found_) {
        // membership is the witness's sign at the window's end, not its bracket: near a root the
        // dense output is not monotone at the ulp level, and a witness already past zero at th_e
        // whose bracket landed a few ulps later would start the next step at or above zero and
        // never be seen again (a lost tick)
        const Witness& w = witnesses_[c.witness];
        if (!c.forced && witnessAt(w, th_e) < 0) continue;
        if (w.kind == WitnessKind::Platform) {
          platform = true;
        } else if (tickDue(ya_.data(), w.pendulum) &&
                   std::find(ticks_due.begin(), ticks_due.end(), w.pendulum) == ticks_due.end()) {
          ticks_due.push_back(w.pendulum);
        }
      }
      std::sort(ticks_due.begin(), ticks_due.end());
      ++report_.counts.events;
      if (debug_)
        std::fprintf(stderr,
                     "event t %.17g th %.17g (step %.6g..%.6g) ticks %zu platform %d mode %d v "
                     "%.6g forced %d\n",
                     t_e, th_e, t0, t1, ticks_due.size(), platform, static_cast<int>(mode()),
                     ya_[StateLayout::kV], static_cast<int>(found_.front().forced));
      recordEnvelope(ya_.data(), t_e);  // the last state before the event
      resolve(ya_.data(), t_e, ticks_due, platform);
      stepper_.restart(t_e, ya_.data());
      recordEnvelope(ya_.data(), t_e);  // and the first after it
      h = h_next;

      // event storm (Zeno): many events without time advancing
      if (t_e - burst_start > storm_window) {
        burst_start = t_e;
        burst = 0;
      }
      if (++burst > opt_.storm_events) {
        std::ostringstream os;
        os << "event storm: " << opt_.storm_events << " events within " << storm_window << " s";
        fail(t_e, os.str());
        break;
      }
      if (last && th_e >= 1.0) break;
    }
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
  report_.final_row = env_.lastRow();
  if (env_.rowsWritten() == 0) report_.final_row.tau = sp_.epsilon * omega0_ * t_fin;

  report_.counts.rhs_evals = stepper_.evaluations();
  report_.ledger.final_J = eq_.energy(y_fin.data());
  report_.ledger.damping_out_J = y_fin[lay_.dampingWork()];
  report_.ledger.friction_out_J = y_fin[lay_.frictionWork()] + friction_settle_J_;
  report_.has_ledger = true;
  report_.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
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
  direct::DirectRun run(rig, sink, options);
  return run.run();
}

}  // namespace metrosync
