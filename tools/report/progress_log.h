// Progress of long work for logs and CI (stderr not a terminal): a line at every 10% of the work,
//   metrosync: run 60% (tau 36676.5 of 61127.2), elapsed 0:06, remaining 0:04
// Work that ends within kQuietSeconds writes nothing (a short run stays silent); once past it,
// each 10% mark crossed writes its line. On a terminal the sweep draws its bar instead.
#pragma once

#include <chrono>
#include <functional>
#include <string>

namespace metrosync {

class ProgressLog {
 public:
  static constexpr double kQuietSeconds = 5.0;

  // what: "run", "sweep"; unit: how `done` and `total` are shown ("tau", "points")
  ProgressLog(std::string what, std::string unit, double total,
              std::function<void(const std::string&)> write, double quiet_s = kQuietSeconds);
  // `done` of `total` so far; elapsed_s < 0: the time since construction
  void update(double done, double elapsed_s = -1.0);

  // Should a command log progress: not --quiet and stderr not a terminal.
  static bool wanted(bool quiet);

 private:
  std::string what_, unit_;
  double total_, quiet_s_;
  std::function<void(const std::string&)> write_;
  int next_decile_ = 1;
  std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
};

// "m:ss" or "h:mm:ss"
std::string clockText(double seconds);

}  // namespace metrosync
