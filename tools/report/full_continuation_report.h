// The files of `metrosync continue --model full` (issue 26, docs/continuation.md), written
// atomically into the output directory:
//   branches.csv       branch,KEY,period,section_<coordinate>...,A_1..A_N,psi_2..psi_N,
//                      max_multiplier,stable,ticks_1..ticks_N,stick_slip,reversals,at_ticks
//                      (one row per orbit along the family; scaled variables: the period in
//                      scaled time, the state on the section, A_i and psi_j averaged over the
//                      orbit as envelope.csv averages them; the events of one period)
//   bifurcations.json  a list of {type: fold|torus|period-doubling|branch|grazing|sliding,
//                      param, value, multipliers [[re, im]...], A, psi, period, detail, branch,
//                      stability_changes}
//   branches.png       A_i, psi_j and the largest multiplier's modulus against KEY, stable solid,
//                      unstable dashed, special points marked
//   summary.json       the command, the start, the section, the family's ends, the special
//                      points counted by type, wall_seconds
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/analysis/periodic_orbit/full_continuation.h"
#include "tools/report/outputs.h"

namespace metrosync {

std::string fullBranchesCsv(const orbit::FullContinuation& r);
// branches.png's gnuplot script (exposed for tests): panels with one set of margins (their axes
// aligned whatever the width of each key) and the |mu| = 1 border drawn as a clipped curve.
std::string fullDiagramScript(const orbit::FullContinuation& r, const std::string& data,
                              const std::string& png);
nlohmann::json fullBifurcationsJson(const orbit::FullContinuation& r);
nlohmann::json fullContinuationSummaryJson(const orbit::FullContinuation& r,
                                           const std::string& rig_name);

// Writes the four files; returns their names (branches.png missing when gnuplot is absent).
std::vector<std::string> writeFullContinuation(const OutputDir& dir,
                                               const orbit::FullContinuation& r,
                                               const std::string& rig_name);

}  // namespace metrosync
