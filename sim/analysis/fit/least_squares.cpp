#include "sim/analysis/fit/least_squares.h"

#include "sim/analysis/fit/ceres_plugin.h"

namespace metrosync {

LocalSolution solveLocal(const LocalProblem& problem) {
  return ceresPlugin().solve(problem);
}

}  // namespace metrosync
