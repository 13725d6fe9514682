// The files of `metrosync fit` and `metrosync measure` (docs/fit.md):
//   fit.json      values, std_errors, identifiable, correlation (in --free order), rms, the noise
//                 level, the verdict, every distinct optimum found, and how the fit was made
//   fit.png       the data against the fitted model (top) and the residuals (bottom), seconds on
//                 the time axis; angles on the left axis, the platform's x (mm) on the right
//   measure.json  each section-3 estimate with its standard error, and the --set lines to use
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/analysis/fit/fit_problem.h"
#include "tools/report/outputs.h"

namespace metrosync {

// A fit's whole answer: what `metrosync fit` writes and prints, and what the Python module's
// `fit` returns (fitJson's dictionary).
struct FitReport {
  std::string rig_path, data_path, model;
  std::vector<FreeParameter> free;      // names, the keys each sets, starting values
  std::vector<std::string> start_from;  // where each start came from: "rig", "--set", ...
  FitOutcome outcome;
  std::string fitted_rig_yaml;  // the rig with every identifiable fitted value (fitted.yaml)
};

nlohmann::json fitJson(const FitReport& report);

// Returns true when DIR/png_name was written (false: no gnuplot, or it failed; a warning).
bool plotFit(const OutputDir& dir, const std::string& png_name, const FitReport& report,
             const std::string& title);

// A JSON number, or null for a value that is not finite.
nlohmann::json numberOrNull(double v);

}  // namespace metrosync
