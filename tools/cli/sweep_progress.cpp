#include "tools/cli/sweep_progress.h"

#include <sys/ioctl.h>

#include <iostream>

#include "sim/analysis/sweep.h"
#include "tools/cli/sweep_summary.h"

namespace metrosync::cli {

SweepProgress::SweepProgress(bool on, bool log, long total, long done_before)
    : on_(on), total_(total), done_(done_before), start_done_(done_before) {
  if (log)
    log_ = std::make_unique<ProgressLog>("sweep", "points", static_cast<double>(total),
                                         [](const std::string& l) { std::cerr << l << "\n"; });
}

void SweepProgress::finished(bool failed) {
  ++done_;
  failed_ += failed;
  if (log_) log_->update(static_cast<double>(done_));
  if (!on_) return;
  const Clock::time_point now = Clock::now();
  if (done_ < total_ && now - last_ < std::chrono::milliseconds(200)) return;
  last_ = now;
  draw();
}

void SweepProgress::done() {
  if (on_ && drawn_) std::cerr << "\n";
}

void SweepProgress::draw() {
  const double elapsed = secondsSince(t0_);
  const long run = done_ - start_done_;
  const double rate = elapsed > 0 && run > 0 ? run / elapsed : 0.0;
  const double eta = rate > 0 ? (total_ - done_) / rate : -1.0;
  winsize ws{};
  const int width = ::ioctl(2, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 20 ? ws.ws_col - 1 : 79;
  // back to the start of the line, the bar, and clear what a longer bar left behind
  std::cerr << "\r" << progressText(done_, total_, failed_, rate, eta, width) << "\033[K"
            << std::flush;
  drawn_ = true;
}

}  // namespace metrosync::cli
