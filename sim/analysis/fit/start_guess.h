// Starting values for `metrosync fit` from the paper's section-3 shortcuts (section3.h), where
// the key and the data allow (docs/fit.md):
//   metronomes.I.pendulum.decay_rate | damping   the free decay of theta_{I+1}, when every swing
//                                                of it stays below theta_c (no tick)
//   platform.friction.mu                         the linear decay of x, when the board is on a
//                                                spring with every metronome locked (s3A)
//   metronomes.I.escapement.steady_amplitude | impulse   the steady amplitude of theta_{I+1}
//                                                (the last half of the record), eq. J_estimate
// (a network of one platform names them platforms.0.metronomes.I... and platforms.0.friction.mu)
#pragma once

#include <optional>
#include <string>

#include "models/rig.h"
#include "sim/analysis/fit/data_file.h"

namespace metrosync {

struct StartGuess {
  double value = 0.0;
  std::string from;  // "free decay", "linear decay", "steady amplitude"
};

// The shortcut's value for `key`, or nullopt when none applies (the rig's value is then used).
std::optional<StartGuess> section3Guess(const std::string& key, const Rig& rig,
                                        const MeasuredData& data);

}  // namespace metrosync
