// The files of `metrosync continue` (issue 12), written atomically into the output directory:
//   branches.csv       branch,KEY,A_1..A_N,psi_2..psi_N,stable,max_real,ticking,platform,s,weight
//                      (one row per point, in order along each branch; stable 1/0; max_real the
//                      largest real part of the eigenvalues; ticking the metronomes whose
//                      escapement is on; platform beta's regime: stuck s <= 1, stick-slip
//                      1 < s <= sqrt(1 + pi^2/4), slip above; s = |Z| / mu; weight the
//                      escapement formula's weight of a border state, nan otherwise)
//   bifurcations.json  a list of {type: fold|hopf|branch|border, param, value, A, psi,
//                      eigenvalues [[re, im]...], detail, branch, stability_changes, lyapunov
//                      (hopf)}
//   branches.png       the diagram (tools/report/continuation_diagram.h)
//   summary.json       the command, the start, the branches (points, why each end stopped, whether
//                      --max-points did), the special points counted by type, the families, the
//                      cycles (points, budget, end, folds with their check); with --fold param2,
//                      fold_curves and hopf_curves
//   families.csv       family,KEY,A_i_min,A_i_max..,psi_j_min,psi_j_max..,closed: each neutral
//                      family's extent
//   cycles.csv         cycle,KEY,period,A_i_min,A_i_max..,psi_j_min,psi_j_max..,stable,
//                      max_multiplier,A_i_0..,psi_j_0..: (A_i_0, psi_j_0) a state on the cycle
//   fold_curve.csv     (--fold) fold,KEY,KEY2,A_1..A_N,psi_2..psi_N: each fold's curve
//   fold_curve.png     (--fold) the curves in the (KEY, KEY2) plane
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/analysis/continuation/result.h"
#include "tools/report/outputs.h"

namespace metrosync {

std::string branchesCsv(const continuation::ContinuationResult& r);
// families.csv: per point of each neutral family, the range of A_i and psi_j over its members.
std::string familiesCsv(const continuation::ContinuationResult& r);
// cycles.csv: per point of each Hopf point's limit cycle, its period and extremes.
std::string cyclesCsv(const continuation::ContinuationResult& r);
// fold_curve.csv (kind Fold) or hopf_curve.csv (kind Hopf, with the frequency omega).
std::string foldCurveCsv(const continuation::ContinuationResult& r, continuation::CurveKind kind);
nlohmann::json bifurcationsJson(const continuation::ContinuationResult& r);
nlohmann::json continuationSummaryJson(const continuation::ContinuationResult& r,
                                       const std::string& rig_name);

// Writes the four files; returns their names (branches.png missing when gnuplot is absent).
std::vector<std::string> writeContinuation(const OutputDir& dir,
                                           const continuation::ContinuationResult& r,
                                           const std::string& rig_name);

}  // namespace metrosync
