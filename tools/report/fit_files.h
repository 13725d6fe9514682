// The files of `metrosync fit` and `metrosync measure` (docs/fit.md):
//   fit.json      values, std_errors, identifiable, correlation (in --free order), rms (rad),
//                 rms_by_column, evaluations, and how the fit was made
//   fit.png       the data against the fitted model (top) and the residuals (bottom), seconds on
//                 the time axis; angles on the left axis, the platform's x (mm) on the right
//   measure.json  each section-3 estimate with its standard error, and the --set lines to use
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/analysis/fit/least_squares.h"
#include "tools/report/outputs.h"

namespace metrosync {

// What fit.json says besides the result itself.
struct FitContext {
  std::string rig_path, data_path, model;
  std::vector<double> starts;           // starting values, in --free order
  std::vector<std::string> start_from;  // where each came from: "rig", "free decay", ...
};

nlohmann::json fitJson(const FitSetup& setup, const FitResult& result, const FitContext& ctx);

// Returns true when DIR/png_name was written (false: no gnuplot, or it failed; a warning).
bool plotFit(const OutputDir& dir, const std::string& png_name, const FitSetup& setup,
             const FitResult& result, const std::string& title);

// A JSON number, or null for a value that is not finite.
nlohmann::json numberOrNull(double v);

}  // namespace metrosync
