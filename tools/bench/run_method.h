// `metrosync run` itself as a method of the bench, "run:INTEGRATOR:ACCURACY" (issue 36): the built
// binary run as a user runs it on a scene's rig file,
//   metrosync run RIG --quiet --no-plot --set simulation.accuracy=A --set simulation.integrator=I
//     --out TMP
// `repeat` times. Its time is the median of summary.json's wall_seconds (the integration with its
// recording), beside the median of engine_seconds and of each run's wall_seconds /
// engine_seconds; its final state is trajectory.csv's last row (the state at t_end, in the rig's
// units) as the bench's scaled state; its counts are summary.json's. The integrators are the
// direct engine's (the engine `run` chooses for them).
#pragma once

#include <string>
#include <vector>

#include "tools/bench/bench_scene.h"

namespace metrosync::bench {

// The metrosync binary the method runs: --metrosync PATH (set before the first use), else
// `metrosync` beside this program's own binary (both are built into build/).
void setMetrosyncPath(const std::string& path);
const std::string& metrosyncPath();
// "" when the binary is there, else why the method is unavailable
std::string runMethodMissing();

// The direct engine's integrators.
std::vector<std::string> runIntegratorNames();

struct RunCall {
  RunResult result;  // wall_s: the median wall_seconds; cpu_s: NaN (not measured)
  int runs = 0;      // runs behind the medians
  std::string command;
};

// `repeat` runs of `scene` (a rig file: scene.path) with `method`; every run stopped after
// timeout_s > 0. A run that fails, or whose files cannot be read, makes the call's result
// complete = false with why.
RunCall runMetrosyncCommand(const Scene& scene, const Method& method, int repeat, double timeout_s);

// The numbers of a CSV file's last line (read from the file's end: trajectory.csv can be large);
// empty when the file cannot be read or its last line is not all numbers.
std::vector<double> lastCsvRow(const std::string& path);

}  // namespace metrosync::bench
