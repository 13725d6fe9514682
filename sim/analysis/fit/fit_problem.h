// What `metrosync fit` is asked and what it answers (docs/fit.md), as values: the free
// parameters (each one value written to a list of rig keys: `metronomes.*.X` is one shared value),
// the data, the model, and the result -- values, standard errors, identifiability, every distinct
// optimum found, the noise level and the verdict. The command (tools/cli/fit.h) and the Python
// module build a FitProblem and read a FitOutcome; fit_strategy.h gets one from the other.
#pragma once

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "models/rig.h"
#include "sim/analysis/fit/data_file.h"
#include "sim/engines/engine.h"

namespace metrosync {

struct FreeParameter {
  std::string name;               // as the user wrote it: "metronomes.*.pendulum.damping"
  std::vector<std::string> keys;  // the rig keys it sets, all to the one value
  double start = 0.0;             // the starting value
  double scale = 1.0;             // its typical size (> 0): the solver works on value / scale
  double lower = -HUGE_VAL;       // lower bound (0 for a key that cannot be negative)
  // A standard error at least max(|value|, size_floor) determines nothing: 0 for a key that
  // cannot be negative (its own size is the measure), a typical size for a signed one (a start
  // angle near 0 can be well determined)
  double size_floor = 0.0;
  // The section-3 shortcut's value (start_guess.h) where one applies and the start is given with
  // --set (used as given, so the shortcut is only a further starting point: fit_strategy.h)
  std::optional<double> shortcut;
};

// One measured value: `quantity` indexes FitOutcome::quantity_names; `group` collects quantities
// of one unit (0 angles, 1 lengths).
struct Observation {
  double t_s = 0.0;
  int quantity = 0;
  int group = 0;
  double value = 0.0;
};

struct FitSettings {
  std::string model = "full";   // "full": every sample; "slow": the slow flow on the swings
  std::optional<double> noise;  // the angles' noise (rad; m when only x is fitted); else estimated
  int starts = 6;               // at most this many starting points (the first is the given one)
  bool local = false;           // only Levenberg-Marquardt on the whole record from each start
  bool profile = false;  // profile every identifiable key (always with the slow flow: it is cheap)
  int max_iterations = 50;  // per local solve
  unsigned seed = 1;        // of the further starting points
};

struct FitProblem {
  std::vector<FreeParameter> free;
  const MeasuredData* data = nullptr;
  const Engine* engine = nullptr;  // of settings.model
  // The rig with the given values (in `free` order) written to their keys. Throws (any
  // std::exception) when the values make no valid rig.
  std::function<Rig(const std::vector<double>&)> rig;
  FitSettings settings;
};

// An optimum the strategy reached from one start.
struct Optimum {
  std::vector<double> values;  // per free parameter
  std::vector<double> start;   // where the search began
  double rms = 0.0;            // as FitOutcome::rms
  bool at_noise = false;       // every column's residual at its noise level
  // its weighted sum of squares above the best's, in variances (likelihood_region.h); NaN when
  // the best has a key held (no common variance to measure it in)
  double rise = std::nan("");
};

// A key's profile: the others refitted with it held at value -+ 2 standard errors; how much the
// weighted sum of squares rose there, in units of its variance (about 4 each side when the
// standard error is right).
struct Profile {
  double lower_at = 0.0, upper_at = 0.0;
  double lower_rise = 0.0, upper_rise = 0.0;
};

struct FitOutcome {
  // per free parameter, in `free` order; values and std_errors empty where not identifiable
  std::vector<std::optional<double>> values, std_errors;
  // the best optimum's own curvature errors, the interval each key's likelihood region spans over
  // every optimum found within it (likelihood_region.h), and which of the two std_errors is:
  // "curvature" or "optima" ("" where not identifiable)
  std::vector<std::optional<double>> curvature_std_errors;
  std::vector<std::optional<std::pair<double, double>>> intervals;
  std::vector<std::string> std_error_from;
  std::vector<double> used;  // what the model ran with: the fitted value, or the start
  std::vector<bool> identifiable;
  std::vector<std::string> not_identifiable_because;            // "" where identifiable
  std::vector<std::vector<std::optional<double>>> correlation;  // (k x k)
  std::vector<std::optional<Profile>> profiles;
  // singular values of the weighted Jacobian with unit columns, largest first (1 and below; one
  // near 0 is a combination of keys the data do not determine)
  std::vector<double> singular_values;
  // the model is smooth in the keys up to this time only (an escapement at grazing, or sensitive
  // dependence late in a long record): standard errors from the record up to it, upper bounds;
  // NaN when smooth throughout
  double smooth_until_s = std::nan("");

  std::vector<std::string> quantity_names;  // "theta_1", "x" (amplitudes of theta for slow)
  std::vector<Observation> observations;
  std::vector<double> predicted;          // the model at `used`, one per observation
  double rms = 0.0;                       // of the first group's residuals (angles, rad)
  std::vector<double> rms_by_quantity;    // per quantity, in its unit
  std::vector<double> noise_by_quantity;  // per quantity (0: unknown)
  std::string noise_from;                 // "--noise", "data" (the high-frequency part), "unknown"

  std::vector<Optimum> optima;  // every distinct one found, best (lowest rms) first
  int evaluations = 0;          // model runs
  int jacobians = 0;            // runs of its derivatives (model_jacobian.h)
  int iterations = 0;           // of the final solve
  bool solver_converged = false;
  bool converged = false;  // solver converged and the residual at the noise level (see note)
  std::string note;        // why converged is what it is, in a sentence
  std::string solver_summary;
  std::string
      strategy;  // what was done, e.g. "windows of 0.6, 1.2, ... 38.5 s, then the whole record"
  std::vector<std::string> warnings;  // for the user: columns not used, ...
};

}  // namespace metrosync
