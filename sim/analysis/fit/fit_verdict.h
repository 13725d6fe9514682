// The verdict of a fit (docs/fit.md): `converged` is true only when the solver converged and the
// residual of every measured column is at its noise level -- within kNoiseTolerance of it -- or,
// when the noise level is not known well (no --noise, and the data too coarse to estimate it),
// when the solver converged and the note says that the residual was not checked. `note` says
// which, in a sentence a user can act on, and where the model is smooth in the keys only over a
// first part of the record (standard errors from that part, upper bounds).
#pragma once

#include <string>
#include <vector>

#include "sim/analysis/fit/fit_problem.h"

namespace metrosync {

// A residual within this factor of the noise is at the noise level: the estimate is good to a
// few percent, and a systematic error of 0.75 noise levels (rms sqrt(1.25^2 - 1)) is already
// visible in the residuals.
inline constexpr double kNoiseTolerance = 1.25;

// Every quantity with a known noise (> 0) has its rms within kNoiseTolerance of it, and at least
// one has.
bool atNoiseLevel(const std::vector<double>& rms_by_quantity, const std::vector<double>& noise);

// Sets out.converged and out.note from out.solver_converged, the residuals and the noise.
// noise_reliable: the noise was given or estimated well; slow: the slow flow was fitted.
void judgeFit(FitOutcome& out, bool noise_reliable, bool slow);

}  // namespace metrosync
