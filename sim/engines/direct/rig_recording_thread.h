// A single rig's recorder (rig_recorder.h) on a thread of its own (sim/record/recording_thread.h):
// the run's thread writes each kept step's start, size, state, end state and stages (what the
// step's dense output is made of) and each event's state as records; the recording thread loads
// each step into the recorder's own stepper and makes the same rows from it as the run's thread
// would (rig_recording.h decides which thread records: RunSink::recordingThread()).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/engines/direct/rig_recorder.h"
#include "sim/record/recording_thread.h"

namespace metrosync::direct {
// Internal linkage on purpose: see direct_model.h (one includer, direct_engine.cpp).
namespace {

template <int N>
class RigRecordingThread {
 public:
  using Stepper = ModelStepper<N>;
  explicit RigRecordingThread(RigRecorder<N>& rec);

  void start(const double* y, PlatformMode mode) { state(Tag::Start, 0.0, mode, y); }
  void step(const Stepper& s, double t_limit, bool inclusive, PlatformMode mode);
  void eventRow(const char* kind, const double* y, double t, PlatformMode mode) {
    state(Tag::EventRow, t, mode, y, kindCode(kind));
  }
  void snapshot(const double* y, double t, PlatformMode mode) { state(Tag::Snapshot, t, mode, y); }
  void eventRecord(const char* kind, int j, const double* y, double t, PlatformMode mode) {
    state(Tag::EventRecord, t, mode, y, kindCode(kind), j);
  }
  void last(const double* y, double t, PlatformMode mode) { state(Tag::Last, t, mode, y); }
  // Waits for every record to be made into rows. Rethrows what the recording thread threw.
  void finish() { thread_.drain(); }

 private:
  enum class Tag { Start, Step, EventRow, Snapshot, EventRecord, Last };
  static constexpr const char* kKinds[] = {"tick", "stick", "slip"};
  static int kindCode(const char* kind) {
    for (int k = 0; k < 3; ++k)
      if (std::strcmp(kind, kKinds[k]) == 0) return k;
    throw std::logic_error(std::string("unknown event kind ") + kind);
  }
  // a state's record: tag, t, mode, kind, j, then the state (dim)
  static constexpr size_t kStateHead = 5;
  // a step's record: tag, t0, h, mode, t_limit, inclusive, then y0, y1, the stages (dim each)
  static constexpr size_t kStepHead = 6;
  void state(Tag tag, double t, PlatformMode mode, const double* y, int kind = 0, int j = -1);
  void consume(const double* block, size_t size);
  size_t stepDoubles() const { return kStepHead + (2 + stages_) * dim_; }

  RigRecorder<N>& rec_;
  size_t dim_;
  int stages_;
  RecordingThread thread_;  // last: started once the rest is set up
};

template <int N>
RigRecordingThread<N>::RigRecordingThread(RigRecorder<N>& rec)
    : rec_(rec),
      dim_(static_cast<size_t>(rec.dim())),
      stages_(rec.ownStepper().tableau().stages),
      // blocks of about 64 kB, at least four of the largest records
      thread_([this](const double* b, size_t n) { consume(b, n); },
              std::max<size_t>(8192, 4 * (kStepHead + (2 + stages_) * dim_))) {}

template <int N>
void RigRecordingThread<N>::state(Tag tag, double t, PlatformMode mode, const double* y, int kind,
                                  int j) {
  double* r = thread_.reserve(kStateHead + dim_);
  r[0] = static_cast<double>(tag);
  r[1] = t;
  r[2] = static_cast<double>(static_cast<int>(mode));
  r[3] = kind;
  r[4] = j;
  std::copy(y, y + dim_, r + kStateHead);
}

template <int N>
void RigRecordingThread<N>::step(const Stepper& s, double t_limit, bool inclusive,
                                 PlatformMode mode) {
  double* r = thread_.reserve(stepDoubles());
  r[0] = static_cast<double>(Tag::Step);
  r[1] = s.t();
  r[2] = s.h();
  r[3] = static_cast<double>(static_cast<int>(mode));
  r[4] = t_limit;
  r[5] = inclusive ? 1.0 : 0.0;
  double* out = std::copy(s.y(), s.y() + dim_, r + kStepHead);
  out = std::copy(s.y1(), s.y1() + dim_, out);
  std::copy(s.stagesData(), s.stagesData() + static_cast<size_t>(stages_) * dim_, out);
}

// On the recording thread: every record of a block, in order.
template <int N>
void RigRecordingThread<N>::consume(const double* block, size_t size) {
  for (size_t at = 0; at < size;) {
    const double* r = block + at;
    const auto tag = static_cast<Tag>(static_cast<int>(r[0]));
    if (tag == Tag::Step) {
      const auto mode = static_cast<PlatformMode>(static_cast<int>(r[3]));
      const double* y0 = r + kStepHead;
      rec_.ownStepper().load(r[1], r[2], y0, y0 + dim_, y0 + 2 * dim_);
      rec_.ownDynamics().mode = mode;  // the interpolant's extra stages
      rec_.sampleLoaded(r[4], r[5] != 0.0, mode);
      at += stepDoubles();
      continue;
    }
    const double t = r[1];
    const auto mode = static_cast<PlatformMode>(static_cast<int>(r[2]));
    const char* kind = kKinds[static_cast<int>(r[3])];
    const double* y = r + kStateHead;
    switch (tag) {
      case Tag::Start:
        rec_.start(y, mode);
        break;
      case Tag::EventRow:
        rec_.eventRow(kind, y, t, mode);
        break;
      case Tag::Snapshot:
        rec_.snapshot(y, t, mode);
        break;
      case Tag::EventRecord:
        rec_.eventRecord(kind, static_cast<int>(r[4]), y, t, mode);
        break;
      case Tag::Last:
        rec_.last(y, t, mode);
        break;
      case Tag::Step:
        break;
    }
    at += kStateHead + dim_;
  }
}

}  // namespace
}  // namespace metrosync::direct
