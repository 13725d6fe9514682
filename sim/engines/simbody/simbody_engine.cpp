// The Simbody engine's one entry: a network's system (models/simbody/platform_system.h), run by
// the one run loop (platform_run.h), recorded by one recorder into the one sink: a single rig's
// rows in the rig's units (its trajectory, envelope, event rows and record) when the network is a
// single rig, the network's states (network::Layout) when the sink wants them.
#include "sim/engines/simbody/simbody_engine.h"

#include <algorithm>
#include <memory>

#include "base/constants.h"
#include "models/scaling.h"
#include "models/simbody/platform_system.h"
#include "sim/engines/simbody/platform_run.h"
#include "sim/record/envelope_quadrature.h"
#include "sim/record/failure_text.h"
#include "sim/record/trajectory_row.h"

namespace metrosync {

namespace {

std::vector<bool> activeMask(const Rig& rig) {
  std::vector<bool> a;
  for (const auto& m : rig.metronomes) a.push_back(!m.locked);
  return a;
}

// A single rig's rows from the run's states: in the rig's units, the envelope in scaled time.
class RigRows {
 public:
  RigRows(const Rig& rig, const PlatformSystem& ps, RunSink& sink)
      : rig_(rig),
        sp_(computeScaled(rig_)),
        ps_(ps),
        sink_(sink),
        n_(static_cast<int>(rig_.metronomes.size())),
        omega0_(1.0 / sp_.time_scale_s),
        env_(sp_.epsilon, activeMask(rig_), rig_.sim.t_end_s * omega0_, sink),
        want_envelope_(sink.wantsEnvelope()),
        pendulum_(n_, -1) {
    for (int j = 0; j < ps.numPendulums(); ++j) pendulum_[ps.equations().pendulum(j).rig_index] = j;
    rows_ = TrajectoryRow(rig_, sp_, pendulum_);
  }
  double timeScale() const { return sp_.time_scale_s; }
  // t (seconds) in the unit of the rows' t: the rig's (seconds, or scaled time)
  double rowTime(double t) const { return rig_.units == Units::Scaled ? t * omega0_ : t; }

  // (the envelope's samples: not needed, the stretches give it)
  void sample(const SimTK::State& s, double t, bool row, bool) {
    if (row) recordTrajectory(s, t);
  }
  void restartAt(const SimTK::State& s);
  void stretchTo(const SimTK::State& s);
  void eventRow(const char* kind, const SimTK::State& s) {
    sink_.eventRow(kind, makeRow(s, s.getTime()));
  }
  void snapshotBefore(const SimTK::State& s) { before_ = makeRow(s, s.getTime()); }
  void recordEvent(const char* kind, int metronome, const SimTK::State& s) {
    sink_.eventRecord(kind, metronome, before_, makeRow(s, s.getTime()));
  }
  // the last trajectory row and the period it closes (SPEC 3 final)
  void finish(const SimTK::State& s, RunReport& report) {
    recordTrajectory(s, s.getTime());
    report.final_trajectory_row = std::move(last_row_);
    if (want_envelope_) report.final_row = env_.finish();
  }
  std::string failureText(double t, const std::string& why) const {
    return metrosync::failureText(t, why, &sp_, rig_.units == Units::Scaled);
  }

 private:
  double theta(const SimTK::State& s, int i) const {
    return pendulum_[i] < 0 ? 0.0 : ps_.theta(s, pendulum_[i]);
  }
  double thetadot(const SimTK::State& s, int i) const {
    return pendulum_[i] < 0 ? 0.0 : ps_.thetadot(s, pendulum_[i]);
  }
  int platformColumn(const SimTK::State& s) const {
    const bool set_valued = ps_.contact(0) != nullptr;
    return TrajectoryRow::column(
        set_valued, set_valued ? static_cast<int>(ps_.contact(0)->mode(s)) : 0, ps_.xdot(s, 0));
  }
  std::vector<double> makeRow(const SimTK::State& s, double t) const;
  void recordTrajectory(const SimTK::State& s, double t) {
    std::vector<double> row = makeRow(s, t);
    sink_.trajectoryRow(row);
    last_row_ = std::move(row);
  }

  void envelopeState(const SimTK::State& s, double* th, double* w) const;

  const Rig rig_;
  ScaledParams sp_;
  const PlatformSystem& ps_;
  RunSink& sink_;
  int n_;
  double omega0_ = 1;
  EnvelopeQuadrature env_;
  bool want_envelope_;
  std::vector<int> pendulum_;          // (metronomes) its swinging pendulum in the system, or -1
  TrajectoryRow rows_{rig_, sp_, {}};  // the rows' maker, both engines' (trajectory_row.h)
  std::vector<double> before_;         // the state before the event being recorded (events.csv)
  std::vector<double> last_row_;       // the last trajectory row (RunReport::final_trajectory_row)
  // the current stretch's start: t, the state and its derivative; a state to interpolate into
  double seg_t_ = 0.0;
  SimTK::Vector seg_y_, seg_yd_;
  std::unique_ptr<SimTK::State> scratch_;
  bool started_ = false;
};

std::vector<double> RigRows::makeRow(const SimTK::State& s, double t) const {
  std::vector<double> row;
  rows_.fill(
      row, t, ps_.x(s, 0), ps_.xdot(s, 0), [&](int j) { return ps_.theta(s, j); },
      [&](int j) { return ps_.thetadot(s, j); }, platformColumn(s));
  return row;
}

// The envelope's view of a state: every metronome's scaled angle and rate (a locked one 0).
void RigRows::envelopeState(const SimTK::State& s, double* th, double* w) const {
  for (int i = 0; i < n_; ++i) {
    th[i] = theta(s, i) / sp_.angle_scale;
    w[i] = thetadot(s, i) / (sp_.angle_scale * omega0_);
  }
}

void RigRows::restartAt(const SimTK::State& s) {
  if (!want_envelope_) return;
  ps_.system().realize(s, SimTK::Stage::Acceleration);  // its derivative, for the interpolant
  if (!started_) {                                      // the start's envelope row
    std::vector<double> th(n_), w(n_);
    envelopeState(s, th.data(), w.data());
    env_.start(th.data(), w.data());
    scratch_ = std::make_unique<SimTK::State>(s);
    started_ = true;
  }
  seg_t_ = s.getTime();
  seg_y_ = s.getY();
  seg_yd_ = s.getYDot();
}

// The stretch from the last start to s on Simbody's own interpolant between the two (cubic
// Hermite: Hairer, Norsett, Wanner, "Solving ODEs I", II.6, as Integrator interpolates).
void RigRows::stretchTo(const SimTK::State& s) {
  if (!want_envelope_ || !(s.getTime() > seg_t_)) return;
  const double t0 = seg_t_, h = s.getTime() - seg_t_;
  const SimTK::Vector &y1 = s.getY(), &yd1 = s.getYDot();
  SimTK::Vector& y = scratch_->updY();
  env_.stretchAt(t0 * omega0_, s.getTime() * omega0_, [&](double tau_t, double* th, double* w) {
    const double u = std::clamp((tau_t / omega0_ - t0) / h, 0.0, 1.0);
    for (int k = 0; k < y.size(); ++k) {
      const double y0 = seg_y_[k], d = y1[k] - y0;
      y[k] = (1 - u) * y0 + u * y1[k] +
             u * (u - 1) * ((1 - 2 * u) * d + (u - 1) * h * seg_yd_[k] + u * h * yd1[k]);
    }
    envelopeState(*scratch_, th, w);
  });
  seg_t_ = s.getTime();
  seg_y_ = y1;
  seg_yd_ = yd1;
}

// The one recorder: a single rig's rows (when the network is one), the network's states (when the
// sink wants them), and the final state for the report either way.
class Recorder : public RunRecorder {
 public:
  Recorder(const Network& net, const PlatformSystem& ps, RunSink& sink)
      : net_(net), ps_(ps), sink_(sink), states_(sink.wantsStates()) {
    if (net.isSingleRig()) rows_ = std::make_unique<RigRows>(net.toSingleRig(), ps, sink);
  }
  bool singleRig() const { return rows_ != nullptr; }
  // the rig's 1/omega0 for a single rig, else the network's (Network::unionRig)
  double timeScale() const {
    return rows_ ? rows_->timeScale() : computeScaled(net_.unionRig()).time_scale_s;
  }
  std::vector<double>& finalState() { return y_; }

  double sampleInterval() const override { return net_.sim.sample_s; }
  void sample(const SimTK::State& s, double t, bool row, bool envelope) override {
    if (rows_) rows_->sample(s, t, row, envelope);
    if (states_ && row) recordState(s, t);
  }
  void poll(double t) override { sink_.poll(rows_ ? rows_->rowTime(t) : t); }
  void restartAt(const SimTK::State& s) override {
    if (rows_) rows_->restartAt(s);
  }
  void stretchTo(const SimTK::State& s) override {
    if (rows_) rows_->stretchTo(s);
  }
  bool wantsEventRecords() const override { return rows_ && sink_.wantsEventRecords(); }
  void eventRow(const char* kind, const SimTK::State& s) override {
    if (rows_) rows_->eventRow(kind, s);
  }
  void snapshotBefore(const SimTK::State& s) override {
    if (rows_) rows_->snapshotBefore(s);
  }
  void recordEvent(const char* kind, int metronome, const SimTK::State& s) override {
    if (rows_) rows_->recordEvent(kind, metronome, s);
  }
  // the last sample: the final state (the schedule's samples stop short of the end)
  void finish(const SimTK::State& s) override {
    if (rows_) rows_->finish(s, report_);
    if (states_)
      recordState(s, s.getTime());
    else
      ps_.layoutState(s, y_);
  }
  std::string failureText(double t, const std::string& why) const override {
    return rows_ ? rows_->failureText(t, why) : metrosync::failureText(t, why);
  }
  RunReport& report() { return report_; }

 private:
  void recordState(const SimTK::State& s, double t) {
    ps_.layoutState(s, y_);
    modes_.assign(ps_.numPlatforms(), PlatformMode::Stuck);
    for (int p = 0; p < ps_.numPlatforms(); ++p)
      if (ps_.contact(p)) modes_[p] = ps_.contact(p)->mode(s);
    sink_.stateSample(t, y_, modes_);
  }

  const Network& net_;
  const PlatformSystem& ps_;
  RunSink& sink_;
  const bool states_;
  std::unique_ptr<RigRows> rows_;  // a single rig's
  std::vector<double> y_;
  std::vector<PlatformMode> modes_;
  RunReport report_;
};

}  // namespace

RunReport runSimbody(const Network& net, RunSink& sink) {
  PlatformSystem ps(net);
  Recorder recorder(net, ps, sink);
  RunReport& report = recorder.report();
  report.model = "full";
  report.engine = "simbody";
  report.integrator =
      net.sim.integrator.empty() ? simbodyIntegratorNames().front() : net.sim.integrator;
  report.accuracy = net.sim.accuracy;
  report.has_ledger = true;
  const double time_scale = recorder.timeScale();
  report.fast_period_s = kTwoPi * time_scale;
  const PlatformRunResult r = runPlatforms(ps, report.integrator, time_scale, recorder);
  report.complete = r.complete;
  report.failure = r.failure;
  report.counts = r.counts;
  // a network report's events: its windows and its event rows (as the direct network engine's);
  // a single rig's: its windows (as the direct engine's)
  if (!recorder.singleRig()) report.counts.events += r.forced_stops + r.event_rows;
  report.ledger = r.ledger;
  report.t_end = r.t_end;
  report.final_state = std::move(recorder.finalState());
  report.wall_seconds = r.wall_seconds;
  report.engine_seconds = r.engine_seconds;
  return report;
}

}  // namespace metrosync
