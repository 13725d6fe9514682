// Shared set-ups of the periodic-orbit tests: rigs written inline, runs of the engine, and the
// settled orbit of a rig from its own start.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "models/rig.h"
#include "sim/analysis/periodic_orbit/return_map.h"
#include "sim/analysis/periodic_orbit/shooting.h"

namespace metrosync::orbit::testing {

// One metronome (the paper's nu = 0.7, J = 2.8, theta_c = 0.9) on a platform held still, scaled
// units, epsilon 0.073, started at amplitude A0, run for tau.
Rig singleFixed(double A0 = 1.9, double tau = 100.0);

// A shipped rig (path relative to the source tree) with overrides.
Rig shipped(const std::string& path, const std::vector<std::string>& sets = {});

// The rig run to its end by the engine at `accuracy`: the final state (scaled).
Vec finalState(const Rig& rig, const ScaledModel& model, double accuracy);

// The orbit the rig's own start settles to: its run's end put on the section, then Newton.
Orbit settledOrbit(const ReturnMap& map);

}  // namespace metrosync::orbit::testing
