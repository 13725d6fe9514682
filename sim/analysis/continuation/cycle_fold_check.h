// A fold of cycles found by the shooting continuation, checked independently by the slow flow
// itself (sim/engines/slow_flow: adaptive Dormand-Prince, every border of the vector field
// switched where it is crossed, nothing shared with the shooting's fixed-step polar map): the
// stable one of the two cycles meeting at the fold, at its own parameter value p_s, is a periodic
// state -- a run started on it stays on its orbit -- while at the mirror value 2 p_f - p_s beyond
// the fold the same start drifts away (no cycle there). A fold where neither neighbour is stable
// cannot be followed by a forward run and is reported unconfirmed.
#pragma once

#include <string>
#include <vector>

#include "sim/analysis/continuation/slow_flow_problem.h"

namespace metrosync::continuation {

struct CycleOnBranch {
  double p = 0.0, period = 0.0;
  bool stable = false;
  std::vector<Vec> orbit;  // reduced polar states along it (SlowFlowProblem::polarState's form)
};

struct FoldCheck {
  bool confirmed = false;
  std::string check;  // what the runs did
};

// The fold at p_f between the branch's cycles `before` and `after` (both on one side of p_f).
FoldCheck checkCycleFold(const SlowFlowProblem& prob, double p_f, const CycleOnBranch& before,
                         const CycleOnBranch& after);

}  // namespace metrosync::continuation
