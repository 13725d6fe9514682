// The bench's final state from a final trajectory row: the one conversion of a row in the rig's
// units to the scaled state the error measures compare (tools/bench/bench_run.h).
#pragma once

#include <vector>

#include "tools/bench/bench_scene.h"

namespace metrosync::bench {

// A final trajectory row in the rig's units (t, x, xdot, theta_1, thetadot_1, ..., theta_N,
// thetadot_N, platform: the engines' final_trajectory_row, trajectory.csv's last row) as the
// bench's scaled final state (xdot, theta_1, thetadot_1, ...); empty when the row is too short.
std::vector<double> scaledFinalState(const Scene& scene, const std::vector<double>& row);

}  // namespace metrosync::bench
