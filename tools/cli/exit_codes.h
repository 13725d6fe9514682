// The exit codes of `metrosync` (SPEC section 5) and the error of a bad command line.
#pragma once

#include <stdexcept>

namespace metrosync::cli {

enum ExitCode : int { kSuccess = 0, kOtherError = 1, kBadInput = 2, kSimulationFailed = 3 };

// A bad command line found after parsing (exit 2); what() is printed after "metrosync: error: ".
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace metrosync::cli
