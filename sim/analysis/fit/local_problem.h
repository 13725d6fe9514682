// One local least-squares problem and its solution (sim/analysis/fit/least_squares.h solves it;
// the Ceres plugin, sim/analysis/fit/ceres_plugin.h, carries it across the plugin's border).
#pragma once

#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace metrosync {

struct LocalProblem {
  // The residuals at the given parameter values (not scaled) into `residuals`
  // (residual_count of them); false when the model fails there (the step is then rejected).
  std::function<bool(const std::vector<double>& values, double* residuals)> residuals;
  // The residuals and their derivatives d residual_i / d value_j into `jacobian` (residual_count
  // x parameters, column-major; the held parameters' columns are not read) at the values; false
  // when the model fails there. Empty: the solver differences `residuals` (difference_step.h).
  std::function<bool(const std::vector<double>& values, double* residuals, double* jacobian)>
      jacobian;
  int residual_count = 0;
  std::vector<double> start;  // per parameter
  std::vector<double> scale;  // typical size (> 0): the solver works on value / scale
  std::vector<double> lower;  // lower bound, -HUGE_VAL for none
  std::vector<bool> held;     // held at start (not fitted)
  int max_iterations = 50;
  // > 0: Cauchy's loss rho(s) = c^2 log(1 + s / c^2), c = loss_scale in the residuals' unit, so
  // that residuals far beyond c (a stretch out of phase, a swing mismeasured) count little
  double loss_scale = 0.0;
};

struct LocalSolution {
  std::vector<double> values;  // the last accepted point (the start when no step was taken)
  int iterations = 0;
  bool converged = false;  // the solver's own criterion (a small change of the cost)
  std::string report;      // Ceres' one-line report
};

}  // namespace metrosync
