// The derivatives of a full-model run with respect to directions q in the rig's parameters
// (issue 36, docs/fit.md): Y = dy/dq, (d x k), at requested times. The engine's run decides every
// event (its windows, sim/analysis/periodic_orbit/engine_trace.h); between two windows the state
// and Y are integrated again, Y by the variational equations dY/dt = J Y + (df/dp) dp/dq
// (PhysicalModel::variationalRates) on the state's steps (Verner 7(6) at the run's accuracy; Y
// rides along uncontrolled, as a monodromy matrix does in piece_flow.h), and at each window Y
// jumps by the saltation matrix and the parameters' own term (saltation.h: the event's time
// moving with q, the jump's size depending on it). Between the steps Y is read by cubic Hermite
// interpolation on its values and rates at the step ends: an error of (omega h)^4 / 384 of Y,
// ~5e-6 on the steps of accuracy 1e-8, far below what a Jacobian's use needs (the solver's
// steps, standard errors to 1e-3).
#pragma once

#include <vector>

#include "sim/analysis/periodic_orbit/engine_trace.h"
#include "sim/analysis/periodic_orbit/physical_model.h"

namespace metrosync {

struct SensitivitySettings {
  double accuracy = 1e-8;    // relative local error target of the state (the run's)
  std::vector<double> atol;  // absolute targets of the state's components (d x 1), SI
  double max_step_s = 0.1;   // the longest step (a tenth of the fast period, as the engine's)
};

// Row i: dy_{component[i]}(times[i]) / dq (1 x k), dirs = dp/dq (P x k); a zero row where
// component[i] < 0. `times` ascending, >= 0; a time on a window is after it. `trace`: the run of
// `model`'s rig, in SI (traceOfRecords). Throws std::runtime_error when the integration fails.
orbit::Mat trajectorySensitivities(const orbit::PhysicalModel& model,
                                   const orbit::EngineTrace& trace, const orbit::Mat& dirs,
                                   const std::vector<double>& times,
                                   const std::vector<int>& component,
                                   const SensitivitySettings& settings);

}  // namespace metrosync
