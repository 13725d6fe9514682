// A single board's recording in the direct model (direct_model.h): its files through its recorder
// (rig_recorder.h: trajectory rows on the shared schedule, the envelope from the steps'
// interpolants, event rows and records), called on the run's thread or, when the sink allows it
// (RunSink::recordingThread), handed over to a recording thread (rig_recording_thread.h).
#pragma once

#include <exception>
#include <memory>
#include <vector>

#include "models/rig.h"
#include "models/scaling.h"
#include "sim/engines/direct/model_dynamics.h"
#include "sim/engines/direct/rig_recorder.h"
#include "sim/engines/direct/rig_recording_thread.h"
#include "sim/record/run_report.h"
#include "sim/record/split_timer.h"

namespace metrosync::direct {
// Internal linkage on purpose: see direct_model.h (one includer, direct_engine.cpp).
namespace {

template <int N>
class RigRecording {
 public:
  using Stepper = ModelStepper<N>;
  RigRecording(SplitTimer& timer, const Rig& rig, const ScaledParams& sp, RunSink& sink,
               double period);

  void start(const double* y, PlatformMode mode) {
    RecordingScope rec(timer_);
    if (thread_)
      thread_->start(y, mode);
    else
      rec_.start(y, mode);
  }
  void samplesBefore(Stepper& s, double t_limit, bool inclusive, PlatformMode mode) {
    if (!rec_.rows() && !rec_.envelope()) return;
    RecordingScope rec(timer_);
    if (thread_)
      thread_->step(s, t_limit, inclusive, mode);
    else
      rec_.step(s, t_limit, inclusive, mode);
  }
  void last(const double* y, double t, PlatformMode mode, RunReport& r) {
    RecordingScope rec(timer_);
    r.final_trajectory_row = rec_.row(y, t, mode);  // (the recording thread's too)
    if (thread_)
      thread_->last(y, t, mode);
    else
      rec_.last(y, t, mode);
  }
  void close(RunReport& r);  // the last period (SPEC 3 final)
  void eventRow(const char* kind, const double* y, double t, PlatformMode mode) {
    if (!rec_.eventRows()) return;
    RecordingScope rec(timer_);
    if (thread_)
      thread_->eventRow(kind, y, t, mode);
    else
      rec_.eventRow(kind, y, t, mode);
  }
  void snapshot(const double* y, double t, PlatformMode mode) {
    if (!rec_.eventRecords()) return;
    RecordingScope rec(timer_);
    if (thread_)
      thread_->snapshot(y, t, mode);
    else
      rec_.snapshot(y, t, mode);
  }
  void eventRecord(const char* kind, int j, const double* y, double t, PlatformMode mode) {
    if (!rec_.eventRecords()) return;
    RecordingScope rec(timer_);
    if (thread_)
      thread_->eventRecord(kind, j, y, t, mode);
    else
      rec_.eventRecord(kind, j, y, t, mode);
  }

 private:
  SplitTimer& timer_;
  RigRecorder<N> rec_;
  std::unique_ptr<RigRecordingThread<N>> thread_;  // recording on its own thread, or none
};

// A recording thread pays when the run is long enough to hide its start and its hand-overs, and
// its pendulums few enough that handing a step over (its stages, (2 + stages) x dim doubles)
// costs less than recording it: measured on 2 cores (docs/bench/speed/run.md, the runcost
// variants), a run of 34-67 fast periods of 2-8 metronomes was 1.0-1.6x faster without one, a
// run of 200-2400 periods of 2-8 metronomes 1.1-1.7x faster with one (in most runs: 7-run medians
// vary by ~15%), and 32 and 128 metronomes (dopri5, no extra interpolation stages for the thread
// to take over) 1.0-1.1x and 1.5-1.8x slower with one.
inline bool worthARecordingThread(const Rig& rig, double period) {
  constexpr double kMetronomePeriods = 500.0;  // between the two groups measured
  constexpr int kMostMetronomes = 8;
  const int n = static_cast<int>(rig.metronomes.size());
  return n <= kMostMetronomes && rig.sim.t_end_s / period * n >= kMetronomePeriods;
}

template <int N>
RigRecording<N>::RigRecording(SplitTimer& timer, const Rig& rig, const ScaledParams& sp,
                              RunSink& sink, double period)
    : timer_(timer), rec_(rig, sp, sink) {
  const bool records = rec_.rows() || rec_.envelope() || rec_.eventRows() || rec_.eventRecords();
  const auto offer = sink.recordingThread();
  using Offer = RunSink::RecordingThread;
  if (records && (offer == Offer::Always ||
                  (offer == Offer::WhenLong && worthARecordingThread(rig, period)))) {
    sink.recordingThreadStarted();  // before the first row
    thread_ = std::make_unique<RigRecordingThread<N>>(rec_);
  }
}

// The recording's end: every record made into rows (the recording thread drained), then the
// envelope's final row. What the recording thread threw comes back here.
template <int N>
void RigRecording<N>::close(RunReport& r) {
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

}  // namespace
}  // namespace metrosync::direct
