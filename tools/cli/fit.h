// `metrosync fit RIG DATA.csv --free KEY ...` and `metrosync measure RIG --decay FILE ...`
// (docs/fit.md): the rig's parameters from measured data -- by nonlinear least squares on the
// full model or the slow flow (sim/analysis/fit/fit_strategy.h), or by the paper's section-3
// closed forms (measure.cpp). Registered in tools/cli/every_command.cpp.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tools/report/fit_files.h"

namespace metrosync::cli {

struct FitOptions {
  std::string rig_path, data_path;
  std::vector<std::string> free;  // --free KEY, in order (metronomes.*.X: one shared value)
  std::vector<std::string> sets;  // --set KEY=VALUE, applied before fitting
  std::string model = "full";     // --model full | slow
  std::optional<double> noise;    // --noise SIGMA: the angles' noise (rad; m when only x)
  int starts = 6;                 // --starts N: at most N starting points
  bool local = false;             // --local: Levenberg-Marquardt on the whole record only
  bool profile = false;           // --profile: profile every key (always with --model slow)
  std::string out;                // --out DIR; empty: runs/<rig name>-fit
  bool quiet = false, no_plot = false;
  bool strict = false;  // --strict: sensible ranges (docs/sensible-ranges.md)
};

struct MeasureOptions {
  std::string rig_path;
  std::vector<std::string> sets;
  std::string decay, friction, steady;  // the three experiments' data files (any of them)
  int metronome = 1;                    // --metronome I: whose theta_I the decay and steady use
  std::string out;                      // --out DIR; empty: runs/<rig name>-measure
  bool quiet = false;
  bool strict = false;  // --strict
};

CLI::App* addFitCommand(CLI::App& app, FitOptions& opt);
// 0 fitted; 2 bad command line, rig or data (nothing written); 3 the model fails at the start.
int fitCommand(const FitOptions& opt);

// The fit itself, nothing written (the Python module's fit): bad input throws UsageError or
// RigError; ModelFailure (sim/analysis/fit/model_samples.h) when the model fails at the start.
FitReport runFit(const FitOptions& opt);

CLI::App* addMeasureCommand(CLI::App& app, MeasureOptions& opt);
// 0 measured; 2 bad command line, rig or data, or data the closed forms cannot use.
int measureCommand(const MeasureOptions& opt);

}  // namespace metrosync::cli
