// The Simbody engine's entry for a single-platform rig: the rig as a network of one
// (models/simbody/platform_system.h), run by the one run loop (platform_run.h), recorded in the
// rig's files: trajectory rows (at rig.sim.sample_s, by interpolation), envelope samples on the
// shared schedule and on both sides of every event, event rows and the event record.
#include "sim/engines/simbody/simbody_engine.h"

#include <sstream>

#include "models/simbody/platform_system.h"
#include "sim/engines/simbody/platform_run.h"
#include "sim/record/envelope_recorder.h"

namespace metrosync {

namespace {

std::vector<bool> activeMask(const Rig& rig) {
  std::vector<bool> a;
  for (const auto& m : rig.metronomes) a.push_back(!m.locked);
  return a;
}

// A rig's files from the run's states: rows in the rig's units, the envelope in scaled time.
class RigRecorder : public RunRecorder {
 public:
  RigRecorder(const Rig& rig, const PlatformSystem& ps, RunSink& sink, RunReport& report)
      : rig_(rig),
        sp_(computeScaled(rig)),
        ps_(ps),
        sink_(sink),
        report_(report),
        n_(static_cast<int>(rig.metronomes.size())),
        env_(sp_.epsilon, activeMask(rig), sink),
        pendulum_(n_, -1) {
    omega0_ = 1.0 / sp_.time_scale_s;
    for (int j = 0; j < ps.numPendulums(); ++j) pendulum_[ps.equations().pendulum(j).rig_index] = j;
  }
  double timeScale() const { return sp_.time_scale_s; }

  double sampleInterval() const override { return rig_.sim.sample_s; }
  void sample(const SimTK::State& s, double t, bool row, bool envelope) override {
    if (row) recordTrajectory(s, t);
    if (envelope) recordEnvelope(s, t);
  }
  void aroundEvent(const SimTK::State& s, double t) override { recordEnvelope(s, t); }
  bool wantsEventRecords() const override { return sink_.wantsEventRecords(); }
  void eventRow(const char* kind, const SimTK::State& s) override {
    sink_.eventRow(kind, makeRow(s, s.getTime()));
  }
  void snapshotBefore(const SimTK::State& s) override { before_ = makeRow(s, s.getTime()); }
  void recordEvent(const char* kind, int metronome, const SimTK::State& s) override {
    sink_.eventRecord(kind, metronome, before_, makeRow(s, s.getTime()));
  }
  // the last trajectory row and the period it closes (SPEC 3 final)
  void finish(const SimTK::State& s) override {
    recordTrajectory(s, s.getTime());
    recordEnvelope(s, s.getTime());
    report_.final_row = env_.finish();
  }
  std::string failureText(double t, const std::string& why) const override {
    std::ostringstream os;
    // t in the rig's own time unit (seconds, or scaled time for a scaled rig)
    const bool scaled = rig_.units == Units::Scaled;
    os << "simulation failed at t = " << (scaled ? t * omega0_ : t) << (scaled ? "" : " s")
       << " (tau = " << sp_.epsilon * omega0_ * t << "): " << why;
    return os.str();
  }

 private:
  double theta(const SimTK::State& s, int i) const {
    return pendulum_[i] < 0 ? 0.0 : ps_.theta(s, pendulum_[i]);
  }
  double thetadot(const SimTK::State& s, int i) const {
    return pendulum_[i] < 0 ? 0.0 : ps_.thetadot(s, pendulum_[i]);
  }
  int platformColumn(const SimTK::State& s) const {
    if (ps_.contact(0)) return static_cast<int>(ps_.contact(0)->mode(s));
    const double v = ps_.xdot(s, 0);
    return v > 0 ? 1 : (v < 0 ? -1 : 0);
  }
  std::vector<double> makeRow(const SimTK::State& s, double t) const;
  void recordTrajectory(const SimTK::State& s, double t) {
    std::vector<double> row = makeRow(s, t);
    sink_.trajectoryRow(row);
    report_.final_trajectory_row = std::move(row);
  }
  void recordEnvelope(const SimTK::State& s, double t);

  const Rig& rig_;
  ScaledParams sp_;
  const PlatformSystem& ps_;
  RunSink& sink_;
  RunReport& report_;
  int n_;
  EnvelopeRecorder env_;
  std::vector<int> pendulum_;  // (metronomes) its swinging pendulum in the system, or -1
  double omega0_ = 1;
  std::vector<double> before_;  // the state before the event being recorded (events.csv)
  std::vector<double> scratch_th_, scratch_w_;
};

std::vector<double> RigRecorder::makeRow(const SimTK::State& s, double t) const {
  std::vector<double> row;
  row.reserve(4 + 2 * n_);
  const bool scaled = rig_.units == Units::Scaled;
  const double xs = scaled ? 1.0 / sp_.x_scale_m : 1.0;
  const double as = scaled ? 1.0 / sp_.angle_scale : 1.0;
  const double ts = scaled ? omega0_ : 1.0;
  row.push_back(t * ts);
  row.push_back(ps_.x(s, 0) * xs);
  row.push_back(ps_.xdot(s, 0) * xs / ts);
  for (int i = 0; i < n_; ++i) {
    row.push_back(theta(s, i) * as);
    row.push_back(thetadot(s, i) * as / ts);
  }
  row.push_back(platformColumn(s));
  return row;
}

void RigRecorder::recordEnvelope(const SimTK::State& s, double t) {
  scratch_th_.resize(n_);
  scratch_w_.resize(n_);
  for (int i = 0; i < n_; ++i) {
    scratch_th_[i] = theta(s, i) / sp_.angle_scale;
    scratch_w_[i] = thetadot(s, i) / (sp_.angle_scale * omega0_);
  }
  env_.sample(t * omega0_, scratch_th_.data(), scratch_w_.data());
}

}  // namespace

RunReport runFullModel(const Rig& rig, RunSink& sink) {
  PlatformSystem ps(networkOfOne(rig));
  RunReport report;
  report.model = "full";
  report.engine = "simbody";
  report.integrator =
      rig.sim.integrator.empty() ? simbodyIntegratorNames().front() : rig.sim.integrator;
  report.accuracy = rig.sim.accuracy;
  RigRecorder recorder(rig, ps, sink, report);
  const PlatformRunResult r = runPlatforms(ps, report.integrator, recorder.timeScale(), recorder);
  report.complete = r.complete;
  report.failure = r.failure;
  report.counts = r.counts;
  report.ledger = r.ledger;
  report.has_ledger = true;
  report.wall_seconds = r.wall_seconds;
  report.engine_seconds = r.engine_seconds;
  return report;
}

}  // namespace metrosync
