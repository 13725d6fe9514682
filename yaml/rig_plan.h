// Internal to yaml/: the plan pass on a built rig (the run's end, sample interval and estimated
// output against the caller's limits, the integrator's name, starts below the top), each check
// blamed on the key that asked for it.
#pragma once

#include "models/rig.h"
#include "yaml/load_options.h"
#include "yaml/rig_source.h"

namespace metrosync::rigfile {

void checkPlan(const Node& root, const Rig& rig, const Source& src, const LoadOptions& opt);

}  // namespace metrosync::rigfile
