// The direct engine's integrators: the names simulation.integrator accepts and the default.
#pragma once

#include <string>
#include <vector>

#include "models/rig.h"

namespace metrosync {

// Names accepted by simulation.integrator with this engine.
const std::vector<std::string>& directIntegratorNames();

// The integrator used when simulation.integrator is empty, chosen by measurement (see
// tools/bench/direct_speed.py): verner76 while steps are set by the accuracy (few metronomes:
// fewest operations for a given envelope error), dopri5 once the ticks of many metronomes cut
// every step short (more than 8 swinging: each step then ends at an event and the cheapest step,
// 6 evaluations against verner76's 16, wins; measured 1.9x faster at N = 100 with an envelope
// error of 3e-7 at accuracy 1e-8).
std::string defaultDirectIntegrator(const Rig& rig);

}  // namespace metrosync
