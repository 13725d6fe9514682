// How each fitted key moves the full model's parameters (sim/analysis/periodic_orbit/
// physical_model.h: the constants e1.1 is written in, and the start state): dp/dkey, one column
// per free key. A key reaches the equations through an algebraic map -- a unit, a default inertia
// m L^2, the total mass M and the normal force M g, section 3's J-bar from a steady amplitude --
// which is differenced here on the rigs the key's values make (FitProblem::rig), with no
// trajectory in it: central differences over kKeyStep of the key, exact to rounding (~1e-10) where
// the map is linear, O(kKeyStep^2) = 1e-12 where it is not. The trajectory's derivatives along
// these directions are the variational equations' (trajectory_sensitivity.h).
#pragma once

#include <vector>

#include "sim/analysis/fit/fit_problem.h"
#include "sim/analysis/periodic_orbit/physical_model.h"

namespace metrosync {

inline constexpr double kKeyStep = 1e-6;

// dp/dvalue_j (P x k; a column of zeros where `wanted` is false) at `values`, for `model`, the
// model of p.rig(values). Throws std::invalid_argument when a key changes the model's shape (its
// swinging pendulums, its law) or the rig cannot be made on either side.
orbit::Mat keyDirections(const FitProblem& p, const std::vector<double>& values,
                         const std::vector<bool>& wanted, const orbit::PhysicalModel& model);

}  // namespace metrosync
