// One local least-squares solve (docs/fit.md): Ceres Solver's Levenberg-Marquardt on the
// residuals' derivatives where the problem gives them (the full model's exact Jacobian), else on
// central differences of the residual function, each parameter scaled by its typical size,
// bounded below where it cannot be negative, optionally under Cauchy's robust loss. The fit's
// strategy (fit_strategy.h) calls it many times -- on growing windows of the record, from several
// starts; the statistics (fit_statistics.h) come after, in plain Eigen. Nothing here knows about
// rigs or engines.
#pragma once

#include "sim/analysis/fit/local_problem.h"

namespace metrosync {

// Throws std::invalid_argument when the residuals cannot be evaluated at the start.
LocalSolution solveLocal(const LocalProblem& problem);

}  // namespace metrosync
