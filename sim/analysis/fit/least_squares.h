// Nonlinear least squares over a model given as a function (docs/fit.md): Ceres Solver's
// Levenberg-Marquardt on central-difference derivatives, then the standard errors and the
// correlations from the Jacobian at the optimum, sigma^2 (J^T J)^-1, and a verdict per parameter:
// a parameter the data cannot determine -- its Jacobian column is zero, or the covariance is
// singular or larger than the parameter itself -- is held at its start and reported as not
// identifiable, with no value. Nothing here knows about rigs or engines: `predict` does.
#pragma once

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace metrosync {

struct FreeParameter {
  std::string key;
  double start = 0.0;        // the starting value
  double scale = 1.0;        // its typical size (> 0): the solver works on value / scale
  double lower = -HUGE_VAL;  // lower bound (0 for a key that cannot be negative)
};

// One measured value: `quantity` indexes FitSetup::quantity_names; `group` collects quantities
// of one unit (angles, lengths), each group weighted by the inverse of its own residual level.
struct Observation {
  double t_s = 0.0;
  int quantity = 0;
  int group = 0;
  double value = 0.0;
};

struct FitSetup {
  std::vector<FreeParameter> free;
  std::vector<Observation> observations;
  std::vector<std::string> quantity_names;  // "theta_1", "x"
  // The model's value at every observation for the given parameter values (in `free` order).
  // Throws (any std::exception) when the values make no valid rig or the simulation fails: the
  // solver then treats the step as failed.
  std::function<std::vector<double>(const std::vector<double>&)> predict;
  int max_iterations = 50;
};

struct FitResult {
  // per parameter, in `free` order; values and std_errors empty where not identifiable
  std::vector<std::optional<double>> values, std_errors;
  std::vector<double> used;  // what the model ran with: the fitted value, or the start
  std::vector<bool> identifiable;
  std::vector<std::vector<std::optional<double>>> correlation;  // (k x k)
  std::vector<double> predicted;        // the model at `used`, one per observation
  double rms = 0.0;                     // of the residuals of the first group (angles, rad)
  std::vector<double> rms_by_quantity;  // per quantity, in its unit
  int evaluations = 0;                  // model runs
  int iterations = 0;
  bool converged = false;
  std::string solver_summary;  // Ceres' one-line report
};

// Throws std::invalid_argument when the model fails at the start values (the message of
// predict's exception) or the setup is inconsistent.
FitResult fitLeastSquares(const FitSetup& setup);

}  // namespace metrosync
