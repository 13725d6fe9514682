// Uncertainty and identifiability at an optimum (docs/fit.md), the same rule for every model:
// the Jacobian J of the weighted residuals by central differences; its singular values with each
// column scaled to unit length (how independent the keys' effects are); the covariance
// sigma^2 (J^T J)^-1 with sigma^2 = SSR / (observations - keys). A key is not identifiable when
//   its column is zero (the data do not see it), or
//   a singular value vanishes (below kCollinear of the largest) along a direction it leads, or
//   its standard error is at least its own size, max(|value|, size_floor) -- the data cannot tell
//   it from 0.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sim/analysis/fit/fit_problem.h"

namespace metrosync {

// Residuals at parameter values (not scaled); false when the model fails there.
using ResidualFunction = std::function<bool(const std::vector<double>&, double*)>;
// The residuals and their derivatives d r_i / d value_j (column-major, residuals x keys) at
// parameter values (not scaled); false when the model fails there.
using JacobianFunction = std::function<bool(const std::vector<double>&, double*, double*)>;

// Residuals r at `values` (in time order) and J = dr / d(value / scale): the model's own
// derivatives where `jac` gives them (the full model's exact Jacobian), else central differences
// (one-sided where the model fails on one side, as at a bound) over each key's difference step
// (difference_step.h). The longest prefix of the residuals over which the model is smooth and
// nearly linear in every key: where the exact derivative agrees with the secant over ten times
// the difference step (without `jac`: where the differences over tenfold smaller and larger steps
// agree). Past it (an escapement at grazing -- a tick there or not -- or a late phase so
// sensitive to the key that the cost has local minima a few steps apart) the derivative says
// little of the uncertainty, and the standard errors come from the prefix alone: upper bounds,
// the value being fitted to the whole record. Throws std::invalid_argument when the model fails
// at `values`, or on both sides of it.
struct Linearization {
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  int smooth_rows = 0;  // the model is smooth in every key over the first smooth_rows residuals
};
// find_smooth = false: no further differences (smooth_rows = all).
Linearization linearize(const ResidualFunction& f, int residual_count,
                        const std::vector<double>& values, const std::vector<FreeParameter>& free,
                        bool find_smooth = true, const JacobianFunction& jac = {});

// Keys whose Jacobian column is (numerically) zero: the data do not see them.
std::vector<bool> unseenKeys(const Eigen::MatrixXd& J);

struct Uncertainty {
  std::vector<std::optional<double>> std_errors;  // per key; empty for held keys
  std::vector<std::vector<std::optional<double>>> correlation;
  std::vector<double> singular_values;  // of the unit-column J of the keys not held, largest first
  double sigma2 = 0.0;                  // SSR / (observations - keys)
  int worst = -1;                       // the key least determined when one is not, else -1
  std::string why;                      // and why, in words
};
Uncertainty uncertainty(const Linearization& lin, const std::vector<double>& values,
                        const std::vector<FreeParameter>& free, const std::vector<bool>& held);

}  // namespace metrosync
