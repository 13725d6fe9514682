// The central-difference step of a fitted key, the one rule of the solver's derivatives (the Ceres
// plugin, ceres_solve.cpp) and of the standard errors' (fit_statistics.cpp).
//
// The step starts at kDiffStep of the key (in units of its scale): the simulation's own relative
// error (simulation.accuracy, 1e-8 by default) stays 1e-4 below the differences. On a long record
// a key can be determined to 1e-5 of itself (docs/bench/fit.md, seed 2's record 7), where such a
// step moves the late phases by radians and the difference is a secant across a wrapped phase:
// there the covariance was 90 times too small along the valley, and the solver stopped 0.8
// variances above a minimum it could not see. So a step that changes the residuals by more than
// kMaxStepRise variances of their rms (|dr|^2 / (|r|^2 / m)) leaves the region where the model is
// linear in the key, and is shrunk to make about kStepRise, by at most kMinStepFraction: the
// simulation's error stays ~100 times below the residuals' change at the smallest step.
#pragma once

#include <algorithm>
#include <cmath>

namespace metrosync {

inline constexpr double kDiffStep = 1e-4;
inline constexpr double kMaxStepRise = 4.0;
inline constexpr double kStepRise = 1.0;
inline constexpr double kMinStepFraction = 1e-3;

// The first step of a key at x (in units of its scale).
inline double firstDifferenceStep(double x) {
  return kDiffStep * std::max(std::abs(x), 1.0);
}

// After a difference over h (first step h0) changed the residuals by `rise` variances: the step
// to take instead, or 0 when h is the one to keep.
inline double shrunkDifferenceStep(double h, double h0, double rise) {
  if (!(rise > kMaxStepRise) || h <= kMinStepFraction * h0) return 0.0;
  return std::max(h * std::sqrt(kStepRise / rise), kMinStepFraction * h0);
}

}  // namespace metrosync
