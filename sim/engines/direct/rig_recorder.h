// A single rig's files from the direct engine's steps: trajectory rows on the shared schedule
// (sim/events/sample_schedule.h) from each step's dense output, the envelope as integrals of the
// steps' interpolants (sim/record/envelope_quadrature.h: each step, or its part before an event,
// is one smooth stretch), event rows and records, all in the rig's units, into the run's sink;
// and, when the sink wants states, the state in network::Layout (a network of one) at every row
// sample and at the end, as the Simbody engine gives it: the sink never chooses the model.
// The direct model (direct_model.h, rig_recording.h) calls it on the run's thread, or hands its
// steps over to a recording thread that calls it there (rig_recording_thread.h): the same calls on
// the same numbers, so the same files to the bit.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "base/constants.h"
#include "models/network_equations.h"
#include "models/rig.h"
#include "models/scaling.h"
#include "sim/engines/direct/model_dynamics.h"
#include "sim/events/sample_schedule.h"
#include "sim/record/envelope_quadrature.h"
#include "sim/record/run_report.h"
#include "sim/record/trajectory_row.h"

namespace metrosync::direct {
// Internal linkage on purpose: see direct_model.h (one includer, direct_engine.cpp).
namespace {

template <int N>
class RigRecorder {
 public:
  using Stepper = ModelStepper<N>;
  RigRecorder(const Rig& rig, const ScaledParams& sp, RunSink& sink);

  // The start's trajectory row and envelope row, from the state at t = 0.
  void start(const double* y, PlatformMode mode);
  // The trajectory rows due in the step `taken` holds before t_limit (or at it, if inclusive),
  // and the envelope's stretch from the step's start to t_limit; mode: the platform's during the
  // step. The step is loaded into the recorder's own stepper (Stepper::load) and interpolated
  // there: the run's stepper, its evaluations and its counts stay the engine's alone, and the
  // rows are the same bits on either thread.
  void step(const Stepper& taken, double t_limit, bool inclusive, PlatformMode mode) {
    stepper_.load(taken.t(), taken.h(), taken.y(), taken.y1(), taken.stagesData());
    dyn_.mode = mode;  // the interpolant's extra stages
    sampleLoaded(t_limit, inclusive, mode);
  }
  // The same for a step already loaded into ownStepper() (the recording thread's)
  void sampleLoaded(double t_limit, bool inclusive, PlatformMode mode);
  // An event row (events the regime window sees), the state before an event, and the event
  // record of the state after it (j: the swinging pendulum that ticked, -1 the platform).
  void eventRow(const char* kind, const double* y, double t, PlatformMode mode);
  void snapshot(const double* y, double t, PlatformMode mode) { before_ = makeRow(y, t, mode); }
  void eventRecord(const char* kind, int j, const double* y, double t, PlatformMode mode);
  // The run's last state (at t_end when complete): its trajectory row.
  void last(const double* y, double t, PlatformMode mode);
  // A state's trajectory row (the rig's units), made without the sink: the run's last state in
  // its report, whichever thread records (it reads only what never changes).
  std::vector<double> row(const double* y, double t, PlatformMode mode) const;
  // The envelope's final row (after last()).
  EnvelopeRow finish() { return env_.finish(); }

  // what the sink takes (asked once): event rows, event records, trajectory rows or states on the
  // row schedule, envelope
  bool eventRows() const { return event_rows_; }
  bool eventRecords() const { return event_records_; }
  bool rows() const { return want_rows_ || want_states_; }
  bool envelope() const { return want_envelope_; }
  // the recorder's own equations and stepper: a step handed over from the run's thread is loaded
  // into it (Stepper::load) and interpolated there
  Stepper& ownStepper() { return stepper_; }
  Dynamics<N>& ownDynamics() { return dyn_; }
  int dim() const { return lay_.dim(); }

 private:
  const std::vector<double>& makeRow(const double* y, double t, PlatformMode mode) {
    fillRow(y, t, mode, row_);
    return row_;
  }
  void fillRow(const double* y, double t, PlatformMode mode, std::vector<double>& row) const;
  // the state (a network of one's: models/network_layout.h) to the sink
  void stateSample(const double* y, double t, PlatformMode mode);
  void envelopeState(const double* y, double* theta, double* thetadot) const;
  void nodeEnvelope(const double* angles_rates, double* theta, double* thetadot) const;

  const Rig& rig_;
  ScaledParams sp_;
  network::NetworkEquations eq_;  // its own: the recording thread's (kAnyN's scratch is per object)
  network::BoardLayout lay_;
  RunSink& sink_;
  bool event_rows_, event_records_, want_rows_, want_envelope_, want_states_;
  int n_rig_;
  double omega0_, period_;
  Dynamics<N> dyn_;
  Stepper stepper_;
  SampleSchedule schedule_;
  EnvelopeQuadrature env_;
  std::vector<double> ya_;       // a sample's state
  std::vector<double> nodes_;    // the Gauss nodes' angles and rates (kNodes x 2n)
  std::vector<int> rig_index_;   // (n x 1) each swinging pendulum's metronome
  double inv_angle_, inv_rate_;  // scaled angle and rate per radian and radian per second
  TrajectoryRow rows_;           // the rows' maker, both engines' (sim/record/trajectory_row.h)
  // the interpolant's weights at the Gauss nodes of a whole step, for h = 1, by stage row
  double node_w_[ode::detail::DenseTable::kPadRows][EnvelopeQuadrature::kNodes] = {};
  std::vector<double> before_;  // the state before the event being recorded (events.csv)
  std::vector<double> row_;     // the row being written
  std::vector<double> state_;   // a state being sampled (network::Layout)
  std::vector<PlatformMode> modes_{PlatformMode::Stuck};
};

template <int N>
std::vector<bool> activeMetronomes(const Rig& rig) {
  std::vector<bool> a;
  for (const auto& m : rig.metronomes) a.push_back(!m.locked);
  return a;
}

template <int N>
RigRecorder<N>::RigRecorder(const Rig& rig, const ScaledParams& sp, RunSink& sink)
    : rig_(rig),
      sp_(sp),
      eq_(rig),
      lay_(eq_.layout().as<1>()),
      sink_(sink),
      event_rows_(sink.wantsEventRows()),
      event_records_(sink.wantsEventRecords()),
      want_rows_(sink.wantsTrajectory()),
      want_envelope_(sink.wantsEnvelope()),
      want_states_(sink.wantsStates()),
      n_rig_(static_cast<int>(rig.metronomes.size())),
      omega0_(1.0 / sp.time_scale_s),
      period_(kTwoPi / omega0_),
      dyn_(eq_, 1),
      stepper_(ode::rkTableau(rig.sim.integrator.empty() ? defaultDirectIntegrator(rig)
                                                         : rig.sim.integrator),
               lay_.dim(), dyn_),
      schedule_(rig.sim.sample_s, period_, rig.sim.t_end_s, want_rows_ || want_states_, false),
      env_(sp.epsilon, activeMetronomes<N>(rig), rig.sim.t_end_s * omega0_, sink),
      ya_(lay_.dim(), 0.0),
      nodes_(EnvelopeQuadrature::kNodes * 2 * lay_.n, 0.0),
      inv_angle_(1.0 / sp.angle_scale),
      inv_rate_(1.0 / (sp.angle_scale * omega0_)),
      rows_(rig, sp, swingingPendulums(rig)) {
  for (int j = 0; j < lay_.n; ++j) rig_index_.push_back(eq_.pendulum(j).rig_index);
  for (int q = 0; q < EnvelopeQuadrature::kNodes; ++q) {
    double w[ode::detail::DenseTable::kPadRows];
    stepper_.denseWeights(0.5 * (1.0 + EnvelopeQuadrature::kNode[q]), 1.0, w);
    for (int r = 0; r < ode::detail::DenseTable::kPadRows; ++r) node_w_[r][q] = w[r];
  }
}

// --- rows -----------------------------------------------------------------------------------

template <int N>
std::vector<double> RigRecorder<N>::row(const double* y, double t, PlatformMode mode) const {
  std::vector<double> r;
  fillRow(y, t, mode, r);
  return r;
}

template <int N>
void RigRecorder<N>::fillRow(const double* y, double t, PlatformMode mode,
                             std::vector<double>& row) const {
  const double v = y[lay_.v(0)];
  rows_.fill(
      row, t, y[lay_.x(0)], v, [&](int j) { return y[lay_.theta(j)]; },
      [&](int j) { return y[lay_.omega(j)]; },
      TrajectoryRow::column(eq_.friction().setValued(), static_cast<int>(mode), v));
}

// The envelope's view of a state: every metronome's scaled angle and rate, in rig order (a locked
// one stays 0).
template <int N>
void RigRecorder<N>::envelopeState(const double* y, double* theta, double* thetadot) const {
  nodeEnvelope(y + lay_.theta(0), theta, thetadot);
}

// The same from the swinging pendulums' angles then rates (2n values).
template <int N>
void RigRecorder<N>::nodeEnvelope(const double* angles_rates, double* theta,
                                  double* thetadot) const {
  const int n = lay_.n;
  for (int j = 0; j < n; ++j) {
    const int i = rig_index_[j];
    theta[i] = angles_rates[j] * inv_angle_;
    thetadot[i] = angles_rates[n + j] * inv_rate_;
  }
}

template <int N>
void RigRecorder<N>::stateSample(const double* y, double t, PlatformMode mode) {
  state_.assign(y, y + lay_.dim());
  modes_[0] = mode;
  sink_.stateSample(t, state_, modes_);
}

template <int N>
void RigRecorder<N>::start(const double* y, PlatformMode mode) {
  if (want_rows_) sink_.trajectoryRow(makeRow(y, 0.0, mode));
  if (want_states_) stateSample(y, 0.0, mode);
  if (!want_envelope_) return;
  std::vector<double> th(n_rig_, 0.0), w(n_rig_, 0.0);
  envelopeState(y, th.data(), w.data());
  env_.start(th.data(), w.data());
}

template <int N>
void RigRecorder<N>::sampleLoaded(double t_limit, bool inclusive, PlatformMode mode) {
  Stepper& s = stepper_;
  const double t0 = s.t(), h = s.h();
  if (want_rows_ || want_states_) {
    schedule_.takeDue(t_limit, inclusive, [&](double ts, bool, bool) {
      s.interpolate(std::clamp((ts - t0) / h, 0.0, 1.0), ya_.data());
      if (want_rows_) sink_.trajectoryRow(makeRow(ya_.data(), ts, mode));
      if (want_states_) stateSample(ya_.data(), ts, mode);
    });
  }
  if (!want_envelope_ || !(t_limit > t0)) return;
  // the stretch [t0, t_limit] in scaled time; only the angles and rates interpolated, at the
  // Gauss nodes of each piece: a whole step's from the weights of the nodes' fractions, computed
  // once (the usual case), a cut piece's from its own
  const double ta = t0 * omega0_, tb = t_limit * omega0_;
  const bool whole_step = t_limit == t0 + h;
  env_.stretch(ta, tb, [&](double a, double b, double* th, double* w) {
    constexpr int Q = EnvelopeQuadrature::kNodes, R = ode::detail::DenseTable::kPadRows;
    double wq[R][Q];  // by stage row
    if (whole_step && a == ta && b == tb) {
      for (int r = 0; r < R; ++r)
        for (int q = 0; q < Q; ++q) wq[r][q] = h * node_w_[r][q];
    } else {
      for (int q = 0; q < Q; ++q) {
        const double t = EnvelopeQuadrature::nodeTime(a, b, q) / omega0_;
        double w[R];
        s.denseWeights(std::clamp((t - t0) / h, 0.0, 1.0), h, w);
        for (int r = 0; r < R; ++r) wq[r][q] = w[r];
      }
    }
    const int n = lay_.n;
    // (Q x 2n): angles, rates
    s.template interpolateMany<Q, (N > 0 ? 2 * N : ode::kDynamic)>(wq, lay_.theta(0), 2 * n,
                                                                   nodes_.data());
    for (int q = 0; q < Q; ++q)
      nodeEnvelope(nodes_.data() + q * 2 * n, th + q * n_rig_, w + q * n_rig_);
  });
}

template <int N>
void RigRecorder<N>::eventRow(const char* kind, const double* y, double t, PlatformMode mode) {
  sink_.eventRow(kind, makeRow(y, t, mode));
}

template <int N>
void RigRecorder<N>::eventRecord(const char* kind, int j, const double* y, double t,
                                 PlatformMode mode) {
  sink_.eventRecord(kind, j < 0 ? -1 : eq_.pendulum(j).rig_index, before_, makeRow(y, t, mode));
}

template <int N>
void RigRecorder<N>::last(const double* y, double t, PlatformMode mode) {
  if (want_rows_) sink_.trajectoryRow(makeRow(y, t, mode));
  if (want_states_) stateSample(y, t, mode);
}

}  // namespace
}  // namespace metrosync::direct
