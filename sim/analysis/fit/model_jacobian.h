// The exact derivatives of the full model's samples in the fitted keys (issue 36, docs/fit.md):
// d model_i / d value_j at the first n observations of a fit, from one run of the model (its
// rows give the samples, its event records the windows) and one integration of its variational
// equations along the keys' directions (key_directions.h, trajectory_sensitivity.h). Replaces
// the model's differences, key by key, for the solver and the standard errors alike.
#pragma once

#include <vector>

#include "sim/analysis/fit/fit_observations.h"
#include "sim/analysis/fit/fit_problem.h"
#include "sim/analysis/fit/model_samples.h"
#include "sim/analysis/periodic_orbit/physical_model.h"

namespace metrosync {

// Can the model's derivatives be had for this problem's rig (the full model, a friction law that
// gives its partials, contact/friction_partials.h)? Else the fit differences the model.
bool hasModelJacobian(const FitProblem& p, const Rig& rig);

// (n x k): row i the derivative of observation i's model value in each key (unweighted, in the
// observation's unit per the key's), columns of keys not `wanted` zero. `run`: the model at
// `values`, to at least the n-th observation's time. Throws std::invalid_argument or
// std::runtime_error when they cannot be had there.
orbit::Mat modelJacobian(const FitProblem& p, const std::vector<double>& values,
                         const ModelTrajectory& run, const FitData& data, int n,
                         const std::vector<bool>& wanted);

}  // namespace metrosync
