// A sweep's progress on stderr: a bar with the rate and ETA when stderr is a terminal, else a line
// every 10% of a sweep that has run for 5 s (tools/report/progress_log.h).
#pragma once

#include <chrono>
#include <memory>

#include "tools/report/progress_log.h"

namespace metrosync::cli {

class SweepProgress {
 public:
  // on: the bar (stderr a terminal); log: a line every 10% instead
  SweepProgress(bool on, bool log, long total, long done_before);
  void finished(bool failed);  // one more point done
  void done();                 // ends the bar's line

 private:
  void draw();
  using Clock = std::chrono::steady_clock;
  bool on_;
  std::unique_ptr<ProgressLog> log_;
  long total_, done_, start_done_, failed_ = 0;
  bool drawn_ = false;
  Clock::time_point t0_ = Clock::now(), last_{};
};

}  // namespace metrosync::cli
