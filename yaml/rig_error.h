// The error of a rig that cannot be loaded (yaml/rig_loader.h); every part of yaml/ throws it.
#pragma once

#include <stdexcept>

namespace metrosync {

// A rig that cannot be loaded: unreadable file, YAML syntax, unknown key, wrong type, missing key,
// value out of range, bad --set. what() is ready to print as is, e.g.
//   rig.yaml:12:15: metronomes.1.pendulum.mass = -0.02: must be > 0
//   rig.yaml: --set platform.friction.mu=-1: platform.friction.mu = -1: must be >= 0
// (line and column 1-based; list indices 0-based, as in --set).
struct RigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace metrosync
