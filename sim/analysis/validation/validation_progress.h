// The validation's progress lines (sim/analysis/validation/validation.h): one line per run, from
// every worker thread, one at a time.
#pragma once

#include <functional>
#include <mutex>
#include <string>
#include <utility>

#include "sim/analysis/validation/validation_runs.h"

namespace metrosync {

// Progress lines from every thread, one at a time.
class ValidationLog {
 public:
  explicit ValidationLog(std::function<void(const std::string&)> out) : out_(std::move(out)) {}
  void say(const std::string& line) {
    if (!out_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    out_(line);
  }
  // "WHAT: REGIME (12.3 s)", or "WHAT: FAILED (12.3 s) - why"
  void run(const std::string& what, const ModelRun& r);

 private:
  std::function<void(const std::string&)> out_;  // a copy: a temporary's lambda outlives its line
  std::mutex mutex_;
};

}  // namespace metrosync
