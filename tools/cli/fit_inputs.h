// The inputs `metrosync fit` and `metrosync measure` share (docs/fit.md): a rig in physical
// units and a measured data file, their errors turned into the command line's (exit 2).
#pragma once

#include <string>
#include <vector>

#include "models/rig.h"
#include "sim/analysis/fit/data_file.h"

namespace metrosync::cli {

// A rig the commands can fit: loaded with the overrides, in physical units. Throws RigError or
// UsageError.
Rig loadPhysicalRig(const std::string& text, const std::string& name,
                    const std::vector<std::string>& sets);

// The data file, checked against the rig's metronomes. Throws UsageError naming file and line.
MeasuredData loadData(const std::string& path, const Rig& rig);

}  // namespace metrosync::cli
