// How `metrosync fit` finds its optimum (docs/fit.md), robust to starts far from it. The raw-angle
// residual of a long record is multimodal in the phase (a model a few percent off in amplitude,
// and so in frequency, is half a period behind after tens of periods), so from each start:
//   1. windows of the record that grow -- the first two periods, doubled until the whole record --
//      each fitted from the last one's optimum, where the model cannot yet drift out of phase;
//      each under Cauchy's robust loss (a stretch out of phase pulls little) and a weak prior
//      that keeps a key the window does not yet determine where it was;
//   2. the whole record in plain least squares.
// Further starting points (the section-3 shortcuts' values where a --set start hides one, then a
// Halton sequence over [start / 2, 2 start] and [start / 4, 4 start] in turn of each key that
// cannot be negative, start -+ 2 scale of the others), at most settings.starts, while no optimum is
// at the noise level and new optima still turn up; every distinct optimum is kept; probes and
// restarts along the weakest axis around the best (neighbouring optima). At the best:
// keys the data do not determine (fit_statistics.h) are held at their starts and the others fitted
// again; standard errors, correlations, profiles; each key's interval over the likelihood region
// of the optima found (likelihood_region.h); the verdict (fit_verdict.h).
// --model slow: step 2 alone, on the swings' amplitudes (the slow flow is itself an envelope).
#pragma once

#include "sim/analysis/fit/fit_problem.h"

namespace metrosync {

// Throws std::invalid_argument for a problem that cannot be fitted (no sample, fewer
// observations than keys), ModelFailure (model_samples.h) when the model fails at the start.
FitOutcome fitModel(const FitProblem& problem);

}  // namespace metrosync
