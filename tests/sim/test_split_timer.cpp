// The split of a run's wall time into engine and recording (sim/record/split_timer.h): nested
// recording stretches count once, so the recording never exceeds the wall time (a negative
// engine_seconds in summary.json before).
#include <gtest/gtest.h>

#include <chrono>

#include "sim/record/split_timer.h"

namespace metrosync {
namespace {

void spin(double seconds) {
  const auto t0 = std::chrono::steady_clock::now();
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < seconds) {
  }
}

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Held against the stretches' own durations, measured on the same clock, so that a thread
// preempted for a while (a loaded machine) moves both sides alike: the recording is the outer
// stretch once; counting the inner one twice would add its whole length.
TEST(SplitTimer, NestedStretchesCountOnce) {
  const auto t0 = std::chrono::steady_clock::now();
  SplitTimer timer;
  double inner_s = 0.0;
  {
    RecordingScope outer(timer);
    spin(0.002);
    const auto ti = std::chrono::steady_clock::now();
    {
      RecordingScope inner(timer);  // a sample taken while rows are handed over
      spin(0.03);
    }
    inner_s = since(ti);
  }
  const double outer_s = since(t0);
  spin(0.03);  // the engine's part
  const double wall = timer.wallSeconds();
  const double rec = timer.recordingSeconds(wall);
  EXPECT_LE(rec, wall);
  EXPECT_NEAR(rec, outer_s, 0.25 * inner_s) << "inner " << inner_s << " s, wall " << wall << " s";
}

TEST(SplitTimer, OnlyRecordingIsAllRecording) {
  SplitTimer timer;
  {
    RecordingScope s(timer);
    spin(0.01);
  }
  const double wall = timer.wallSeconds();
  EXPECT_LE(timer.recordingSeconds(wall), wall);
  EXPECT_GT(timer.recordingSeconds(wall), 0.5 * wall);
}

}  // namespace
}  // namespace metrosync
