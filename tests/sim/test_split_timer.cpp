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

TEST(SplitTimer, NestedStretchesCountOnce) {
  SplitTimer timer;
  {
    RecordingScope outer(timer);
    spin(0.002);
    {
      RecordingScope inner(timer);  // a sample taken while rows are handed over
      spin(0.03);
    }
  }
  spin(0.03);  // the engine's part
  const double wall = timer.wallSeconds();
  const double rec = timer.recordingSeconds(wall);
  // recording: 32 of ~62 ms; counting the inner stretch twice gave ~62 of 62
  EXPECT_GT(rec, 0.2 * wall);
  EXPECT_LT(rec, 0.8 * wall);
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
