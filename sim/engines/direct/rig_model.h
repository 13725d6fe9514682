// The single rig as the direct run's model (sim/engines/direct/direct_run.h): the rig's minimal
// coordinates (models/network_equations.h: a network of one) with the number N of swinging
// pendulums known to the compiler, its one platform seen by the shared resolver, and its files
// through its recorder (rig_recorder.h: trajectory rows on the shared schedule, the envelope from
// the steps' interpolants, event rows and records), called on the run's thread or, when the sink
// allows it (RunSink::recordingThread), handed over to a recording thread (rig_recording_thread.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "base/constants.h"
#include "models/network_equations.h"
#include "models/rig.h"
#include "models/scaling.h"
#include "sim/engines/direct/direct_integrators.h"
#include "sim/engines/direct/rig_dynamics.h"
#include "sim/engines/direct/rig_recorder.h"
#include "sim/engines/direct/rig_recording_thread.h"
#include "sim/engines/direct/start_state.h"
#include "sim/events/event_system.h"
#include "sim/ode/rk_stepper.h"
#include "sim/ode/rk_tableau.h"
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

// The rig's model: its one platform seen by the resolver through this class itself (on the state
// the window resolves, ev_y_).
template <int N>
class RigModel final : public EventSystem {
 public:
  using Stepper = RigStepper<N>;
  static constexpr int kV = 1;                     // the platform's xdot in the state (lay_.v(0))
  static constexpr bool kHoldingForceRate = true;  // H's rate is known in closed form
  RigModel(SplitTimer& timer, const Rig& rig, RunSink& sink);

  // --- the model (sim/engines/direct/direct_run.h) ----------------------------------------------
  Stepper& stepper() { return stepper_; }
  const RkTableau& tableau() const { return tab_; }
  const network::Layout& layout() const { return lay_; }
  int platforms() const { return 1; }
  int first(int) const { return 0; }
  int count(int) const { return lay_.n; }
  int below(int) const { return -1; }
  bool moves(int) const { return eq_.hasPlatform(); }
  int rigIndex(int j) const { return eq_.pendulum(j).rig_index; }
  const PlatformFriction& contact(int) const { return eq_.friction(); }
  Escapement escapement(int j) const { return eq_.escapement(j); }
  PlatformMode mode(int) const { return dyn_.mode; }
  double slipVelocity(int, const double* y) const { return y[kV]; }
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

  // --- recording (the recorder's, on this thread or on its own) -------------------------------
  void start(const double* y) {
    RecordingScope rec(timer_);
    if (thread_)
      thread_->start(y, dyn_.mode);
    else
      rec_.start(y, dyn_.mode);
  }
  void samplesBefore(Stepper& s, double t_limit, bool inclusive) {
    if (!rec_.rows() && !rec_.envelope()) return;
    RecordingScope rec(timer_);
    if (thread_)
      thread_->step(s, t_limit, inclusive, dyn_.mode);
    else
      rec_.step(s, t_limit, inclusive, dyn_.mode);
  }
  void window(const double*, double) {}  // each step's stretch ends at the window: nothing more
  void last(const double* y, double t, RunReport& r) {
    RecordingScope rec(timer_);
    r.final_trajectory_row = rec_.row(y, t, dyn_.mode);  // (the recording thread's too)
    r.final_state.assign(y, y + lay_.dim());             // a network of one's
    if (thread_)
      thread_->last(y, t, dyn_.mode);
    else
      rec_.last(y, t, dyn_.mode);
  }
  void close(RunReport& r);  // the last period (SPEC 3 final)

  // --- EventSystem (on ev_y_) -------------------------------------------------------------
  double theta(int j) const override { return ev_y_[lay_.theta(j)]; }
  double thetadot(int j) const override { return ev_y_[lay_.omega(j)]; }
  double xdot() const override { return ev_y_[kV]; }
  PlatformMode mode() const override { return dyn_.mode; }
  void setMode(PlatformMode m) override {
    dyn_.mode = m;
    if (m == PlatformMode::Stuck) ev_y_[kV] = 0.0;  // held: the residual of a stop
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
    if (!rec_.eventRows()) return;
    RecordingScope rec(timer_);
    if (thread_)
      thread_->eventRow(kind, ev_y_, ev_t_, dyn_.mode);
    else
      rec_.eventRow(kind, ev_y_, ev_t_, dyn_.mode);
  }
  void snapshotBefore() override {
    if (!rec_.eventRecords()) return;
    RecordingScope rec(timer_);
    if (thread_)
      thread_->snapshot(ev_y_, ev_t_, dyn_.mode);
    else
      rec_.snapshot(ev_y_, ev_t_, dyn_.mode);
  }
  void recordEvent(const char* kind, int j) override {
    if (!rec_.eventRecords()) return;
    RecordingScope rec(timer_);
    if (thread_)
      thread_->eventRecord(kind, j, ev_y_, ev_t_, dyn_.mode);
    else
      rec_.eventRecord(kind, j, ev_y_, ev_t_, dyn_.mode);
  }

 private:
  SplitTimer& timer_;
  const Rig& rig_;
  ScaledParams sp_;
  network::NetworkEquations eq_;
  network::Layout lay_;
  int n_rig_;
  Dynamics<N> dyn_;
  const RkTableau& tab_;
  Stepper stepper_;
  double omega0_ = 1.0, period_ = 1.0;
  double* ev_y_ = nullptr;  // the state the resolver acts on, at time ev_t_
  double ev_t_ = 0.0;
  double mobility_ = 0.0;  // platformMobility() at ev_y_'s angles (0: not computed yet)
  RigRecorder<N> rec_;
  std::unique_ptr<RigRecordingThread<N>> thread_;  // recording on its own thread, or none

  bool worthARecordingThread() const;
};

template <int N>
RigModel<N>::RigModel(SplitTimer& timer, const Rig& rig, RunSink& sink)
    : timer_(timer),
      rig_(rig),
      sp_(computeScaled(rig)),
      eq_(rig),
      lay_(eq_.layout()),
      n_rig_(static_cast<int>(rig.metronomes.size())),
      dyn_(eq_),
      tab_(rkTableau(rig.sim.integrator.empty() ? defaultDirectIntegrator(rig)
                                                : rig.sim.integrator)),
      stepper_(tab_, lay_.dim(), dyn_),
      omega0_(1.0 / sp_.time_scale_s),
      period_(kTwoPi / omega0_),
      rec_(rig, sp_, sink) {
  stepper_.setTolerances(rig.sim.accuracy, scaledTolerances(rig.sim.accuracy, sp_, lay_));
  const bool records = rec_.rows() || rec_.envelope() || rec_.eventRows() || rec_.eventRecords();
  const auto offer = sink.recordingThread();
  using Offer = RunSink::RecordingThread;
  if (records &&
      (offer == Offer::Always || (offer == Offer::WhenLong && worthARecordingThread()))) {
    sink.recordingThreadStarted();  // before the first row
    thread_ = std::make_unique<RigRecordingThread<N>>(rec_);
  }
}

// A recording thread pays when the run is long enough to hide its start and its hand-overs, and
// its pendulums few enough that handing a step over (its stages, (2 + stages) x dim doubles)
// costs less than recording it: measured on 2 cores (docs/bench/speed/run.md, the runcost
// variants), a run of 34-67 fast periods of 2-8 metronomes was 1.0-1.6x faster without one, a
// run of 200-2400 periods of 2-8 metronomes 1.1-1.7x faster with one (in most runs: 7-run medians
// vary by ~15%), and 32 and 128 metronomes (dopri5, no extra interpolation stages for the thread
// to take over) 1.0-1.1x and 1.5-1.8x slower with one.
template <int N>
bool RigModel<N>::worthARecordingThread() const {
  constexpr double kMetronomePeriods = 500.0;  // between the two groups measured
  constexpr int kMostMetronomes = 8;
  return n_rig_ <= kMostMetronomes && tEnd() / period_ * n_rig_ >= kMetronomePeriods;
}

// The recording's end: every record made into rows (the recording thread drained), then the
// envelope's final row. What the recording thread threw comes back here.
template <int N>
void RigModel<N>::close(RunReport& r) {
  std::exception_ptr error;
  if (thread_) {
    RecordingScope rec(timer_);
    try {
      thread_->finish();
    } catch (...) {
      error = std::current_exception();
    }
  }
  if (rec_.envelope()) r.final_row = rec_.finish();
  if (error) std::rethrow_exception(error);
}

template <int N>
std::string RigModel<N>::failureText(double t, const std::string& why) const {
  return metrosync::failureText(t, why, &sp_, rig_.units == Units::Scaled);
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
    const network::PendulumConstants& p = eq_.pendulum(j);
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
