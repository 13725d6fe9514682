// The single rig as the direct run's model (sim/engines/direct/direct_run.h): the rig's minimal
// coordinates (models/minimal_equations.h) with the number N of swinging pendulums known to the
// compiler, its one platform seen by the shared resolver, and its files (trajectory and envelope
// rows on the shared schedule, event rows and records).
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "base/constants.h"
#include "models/minimal_equations.h"
#include "models/rig.h"
#include "models/scaling.h"
#include "sim/engines/direct/direct_integrators.h"
#include "sim/engines/direct/start_state.h"
#include "sim/events/event_system.h"
#include "sim/events/sample_schedule.h"
#include "sim/ode/rk_stepper.h"
#include "sim/ode/rk_tableau.h"
#include "sim/record/envelope_recorder.h"
#include "sim/record/failure_text.h"
#include "sim/record/run_report.h"
#include "sim/record/split_timer.h"

namespace metrosync::direct {
// Internal linkage on purpose (this header has one includer, direct_engine.cpp): the run's
// instantiation over a model of internal linkage is itself internal, so the compiler inlines the
// run's hooks into the step loop as it did when the run lived in that file. With external
// linkage the same run executed 2.8% more instructions (valgrind, peer-n2 at 1e-5:
// tools/bench/instructions.sh; 49.8M against 50.4M for the probe's three runs).
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

// The rig's model: its one platform seen by the resolver through this class itself (on the state
// the window resolves, ev_y_).
template <int N>
class RigModel final : public EventSystem {
 public:
  using Stepper = ode::RkStepperT<Dynamics<N>, stateDim(N), 2>;
  static constexpr bool kHoldingForceRate = true;  // H's rate is known in closed form
  RigModel(SplitTimer& timer, const Rig& rig, RunSink& sink);

  // --- the model (sim/engines/direct/direct_run.h) ----------------------------------------------
  Stepper& stepper() { return stepper_; }
  const RkTableau& tableau() const { return tab_; }
  const StateLayout& layout() const { return lay_; }
  int platforms() const { return 1; }
  int first(int) const { return 0; }
  int count(int) const { return lay_.n; }
  int below(int) const { return -1; }
  bool moves(int) const { return eq_.hasPlatform(); }
  int rigIndex(int j) const { return eq_.pendulum(j).rig_index; }
  const PlatformFriction& contact(int) const { return eq_.friction(); }
  Escapement escapement(int j) const { return eq_.escapement(j); }
  PlatformMode mode(int) const { return dyn_.mode; }
  double slipVelocity(int, const double* y) const { return y[StateLayout::kV]; }
  double holdingForce(int, const double* y) const { return eq_.holdingForce(y); }
  double holdingForceRate(int, const double* y) const { return eq_.holdingForceRate(y); }
  EventSystem& view(int, double* y, double t) {
    ev_y_ = y;
    ev_t_ = t;
    mobility_ = 0.0;
    return *this;
  }
  double period() const { return period_; }
  double maxStepSize() const;
  double accuracy() const { return rig_.sim.accuracy; }
  double tEnd() const { return rig_.sim.t_end_s; }
  double energy(const double* y) const { return eq_.energy(y); }
  double dampingOut(const double* y) const { return y[lay_.dampingWork()]; }
  std::vector<double> startState();
  int metronomes() const { return n_rig_; }
  std::string failureText(double t, const std::string& why) const;

  // --- recording ------------------------------------------------------------------------------
  void start(const double* y) {
    recordTrajectory(y, 0.0);
    recordEnvelope(y, 0.0);
  }
  void samplesBefore(Stepper& s, double t_limit, bool inclusive);
  void window(const double* y, double t) { recordEnvelope(y, t); }
  void last(const double* y, double t, RunReport& r) {
    r.final_trajectory_row = makeRow(y, t);
    recordTrajectory(y, t);
    recordEnvelope(y, t);
  }
  void close(RunReport& r) { r.final_row = env_.finish(); }  // the last period (SPEC 3 final)

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

 private:
  const std::vector<double>& makeRow(const double* y, double t);  // in row_
  void recordTrajectory(const double* y, double t);
  void recordEnvelope(const double* y, double t);

  SplitTimer& timer_;
  const Rig& rig_;
  ScaledParams sp_;
  MetronomeEquations eq_;
  StateLayout lay_;
  RunSink& sink_;
  // what the sink takes (asked once): event rows, event records, trajectory rows, envelope rows
  bool event_rows_, event_records_, want_rows_, want_envelope_;
  int n_rig_;
  EnvelopeRecorder env_;
  Dynamics<N> dyn_;
  const RkTableau& tab_;
  // the ledger's two quadratures (the damping's and friction's work) are not in the stages
  Stepper stepper_;
  double omega0_ = 1.0, period_ = 1.0;
  SampleSchedule schedule_;
  double* ev_y_ = nullptr;      // the state the resolver acts on, at time ev_t_
  std::vector<double> before_;  // the state before the event being recorded (events.csv)
  double ev_t_ = 0.0;
  double mobility_ = 0.0;   // platformMobility() at ev_y_'s angles (0: not computed yet)
  std::vector<double> ya_;  // a sample's state
  std::vector<double> env_th_, env_w_;
  std::vector<double> row_;  // the trajectory row being written
};

template <int N>
RigModel<N>::RigModel(SplitTimer& timer, const Rig& rig, RunSink& sink)
    : timer_(timer),
      rig_(rig),
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
      stepper_(tab_, lay_.dim(), dyn_),
      omega0_(1.0 / sp_.time_scale_s),
      period_(kTwoPi / omega0_),
      schedule_(rig.sim.sample_s, period_, rig.sim.t_end_s, want_rows_, want_envelope_) {
  ya_.resize(lay_.dim());
  env_th_.resize(n_rig_, 0.0);
  env_w_.resize(n_rig_, 0.0);
  stepper_.setTolerances(rig.sim.accuracy, scaledTolerances(rig.sim.accuracy, sp_, lay_));
}

template <int N>
std::string RigModel<N>::failureText(double t, const std::string& why) const {
  return rigFailureText(t, sp_, rig_.units == Units::Scaled, why);
}

// --- recording ------------------------------------------------------------------------------

template <int N>
const std::vector<double>& RigModel<N>::makeRow(const double* y, double t) {
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
    row.push_back(static_cast<int>(dyn_.mode));
  } else {
    const double v = y[StateLayout::kV];
    row.push_back(v > 0 ? 1 : (v < 0 ? -1 : 0));
  }
  return row;
}

template <int N>
void RigModel<N>::recordTrajectory(const double* y, double t) {
  if (!want_rows_) return;
  RecordingScope rec(timer_);
  sink_.trajectoryRow(makeRow(y, t));
}

template <int N>
void RigModel<N>::recordEnvelope(const double* y, double t) {
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
void RigModel<N>::samplesBefore(Stepper& s, double t_limit, bool inclusive) {
  const double t_next = schedule_.next();
  if (!(t_next < t_limit || (inclusive && t_next == t_limit))) return;
  RecordingScope rec(timer_);
  const double t0 = s.t(), h = s.h();
  schedule_.takeDue(t_limit, inclusive, [&](double ts, bool row, bool env) {
    const double th = std::clamp((ts - t0) / h, 0.0, 1.0);
    // an envelope sample needs the angles and rates only (2N of the 2N + 4 components)
    if (row)
      s.interpolate(th, ya_.data());
    else
      s.interpolateRange(th, lay_.theta(0), 2 * lay_.n, ya_.data());
    if (row) recordTrajectory(ya_.data(), ts);
    if (env) recordEnvelope(ya_.data(), ts);
  });
}

// --- the model's start and steps --------------------------------------------------------------

// The rig's start state (the run arms its resolver and settles the platform's mode on it).
template <int N>
std::vector<double> RigModel<N>::startState() {
  std::vector<double> y(lay_.dim(), 0.0);
  writePlatformStart(rig_, eq_.hasPlatform(), lay_, 0, 0, y.data());
  return y;
}

// The largest step: a fraction of the fastest oscillation (pendulums, platform spring), so that a
// step holds at most one extreme of any witness.
template <int N>
double RigModel<N>::maxStepSize() const {
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

}  // namespace
}  // namespace metrosync::direct
