// What a caller of the rig loader (yaml/rig_loader.h, yaml/network_loader.h) adds to the rig's
// own checks.
#pragma once

#include <cmath>
#include <string>
#include <vector>

namespace metrosync {

// What the caller adds to the rig's own checks (docs/rig-limits.md).
struct LoadOptions {
  // A run of the rig may write at most this many bytes (estimateOutput). No limit unless the
  // caller sets one: `run` and `compare` do (kDefaultMaxOutputBytes, --max-output); a sweep point
  // writes no trajectory.
  double max_output_bytes = HUGE_VAL;
  // The integrator names simulation.integrator may take, and how to list them in a message;
  // empty: the name is not checked here (the engine checks it).
  std::vector<std::string> integrators;
  std::string integrator_help;
};

}  // namespace metrosync
