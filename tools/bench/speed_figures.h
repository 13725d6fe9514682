// Issue 36's table from one run of tools/bench/speed.sh: every figure beside its target, with its
// verdict and, where the target is missed, by how much -- `run` and the engine against the
// careful peer at equal final-state error, `run` against its engine, the default rig, the whole
// process, the cost per step and per event, one fit, `continue --all` at N = 32. Read from the
// folder's CSVs (SpeedInputs); a part that was not measured says so. No I/O.
#pragma once

#include <string>
#include <vector>

#include "tools/bench/speed_inputs.h"

namespace metrosync::bench {

struct SpeedFigure {
  std::string what, measured, target;
  std::string verdict;  // "met", "NOT met", "not measured", "reported"
  std::string by;       // where missed, by how much ("" otherwise)
  bool judged() const { return verdict == "met" || verdict == "NOT met"; }
};

// Throws std::invalid_argument (file, line, column) for a malformed CSV.
std::vector<SpeedFigure> speedFigures(const SpeedInputs& in);

// The table (Markdown) and its count of targets met.
std::string figuresMarkdown(const std::vector<SpeedFigure>& figures);

}  // namespace metrosync::bench
