// Splits a run's wall time into the engine's part and the recording's part without a clock call
// per sample: the recording's stretches (taking samples from the interpolant, handing rows to the
// sink) are counted in processor ticks (rdtsc, ~7 ns to read, where the machine has it; the steady
// clock elsewhere), and the run's whole wall time is split in the ratio of the ticks.
#pragma once

#include <chrono>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#define METROSYNC_HAVE_RDTSC 1
#endif

namespace metrosync {

class SplitTimer {
 public:
  SplitTimer() : wall0_(std::chrono::steady_clock::now()), ticks0_(now()) {}

  // Marks the start and the end of a recording stretch. Stretches may nest (a sample taken
  // inside a stretch that hands rows over): only the outermost one counts, so no tick is counted
  // twice.
  void beginRecording() {
    if (depth_++ == 0) mark_ = now();
  }
  void endRecording() {
    if (--depth_ == 0) recording_ += now() - mark_;
  }

  // Wall seconds since construction, and the part of them spent recording.
  double wallSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0_).count();
  }
  double recordingSeconds(double wall_seconds) const {
    const std::uint64_t total = now() - ticks0_;
    return total > 0 ? wall_seconds * static_cast<double>(recording_) / static_cast<double>(total)
                     : 0.0;
  }

 private:
  static std::uint64_t now() {
#ifdef METROSYNC_HAVE_RDTSC
    return __rdtsc();
#else
    return static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
#endif
  }
  std::chrono::steady_clock::time_point wall0_;
  std::uint64_t ticks0_;
  std::uint64_t mark_ = 0, recording_ = 0;
  int depth_ = 0;
};

// Counts the recording stretch of its scope.
class RecordingScope {
 public:
  explicit RecordingScope(SplitTimer& t) : t_(t) { t_.beginRecording(); }
  ~RecordingScope() { t_.endRecording(); }
  RecordingScope(const RecordingScope&) = delete;
  RecordingScope& operator=(const RecordingScope&) = delete;

 private:
  SplitTimer& t_;
};

}  // namespace metrosync
