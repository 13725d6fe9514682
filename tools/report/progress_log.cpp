#include "tools/report/progress_log.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace metrosync {

std::string clockText(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[40];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

ProgressLog::ProgressLog(std::string what, std::string unit, double total,
                         std::function<void(const std::string&)> write, double quiet_s)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      total_(total),
      quiet_s_(quiet_s),
      write_(std::move(write)) {}

bool ProgressLog::wanted(bool quiet) {
  return !quiet && ::isatty(2) == 0;
}

void ProgressLog::update(double done, double elapsed_s) {
  if (!(total_ > 0) || next_decile_ > 10 || !std::isfinite(done)) return;
  const double fraction = std::min(1.0, done / total_);
  const int decile = static_cast<int>(std::floor(fraction * 10 + 1e-9));
  if (decile < next_decile_) return;
  next_decile_ = decile + 1;  // marks passed while quiet are not written later
  if (elapsed_s < 0)
    elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  if (elapsed_s < quiet_s_) return;
  const double remaining = fraction > 0 ? elapsed_s * (1 - fraction) / fraction : 0.0;
  char buf[200];
  std::snprintf(buf, sizeof buf, "metrosync: %s %d%% (%s %.6g of %.6g), elapsed %s, remaining %s",
                what_.c_str(), decile * 10, unit_.c_str(), done, total_,
                clockText(elapsed_s).c_str(), clockText(remaining).c_str());
  write_(buf);
}

}  // namespace metrosync
