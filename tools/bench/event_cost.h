// The measurements behind tools/bench/event_cost_table.h: per scene, one RHS evaluation timed
// alone (the direct engine's equations, NetworkEquations::rhsN with N known to the compiler up
// to kMaxFixedN as in the run, at the rig's start state, a slipping platform), and the direct
// engine's run without samples at each accuracy (its default integrator; `repeat` runs, CPU
// median, the counts of the first).
#pragma once

#include <string>
#include <vector>

#include "models/rig.h"
#include "tools/bench/bench_measure.h"
#include "tools/bench/event_cost_table.h"

namespace metrosync::bench {

struct EventCostOptions {
  std::vector<std::string> scenes;  // rig files
  std::vector<double> accuracies = {1e-6, 1e-9};
};

// CPU seconds of one RHS evaluation of `rig`'s equations (median over batches).
double rhsSeconds(const Rig& rig);

std::vector<EventCostRow> measureEventCost(const EventCostOptions& o, const BenchOptions& c);

}  // namespace metrosync::bench
