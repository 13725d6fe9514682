// A fold of cycles found by the shooting continuation, checked independently by the slow flow
// itself (sim/engines/slow_flow: adaptive Dormand-Prince, every border of the vector field
// switched where it is crossed, nothing shared with the shooting's fixed-step polar map). Of the
// two legs of cycles meeting at the fold, the stable one gives a periodic state: a run started on
// its cycle halfway along its stable stretch, at p_s, stays on that cycle; at the mirror value
// 2 p_f - p_s beyond the fold, where no cycle is, the same start drifts away. A fold where neither
// leg is stable cannot be followed by a forward run and is reported unconfirmed.
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

// The fold at p_f between the branch's two legs (each ordered from the fold outwards).
FoldCheck checkCycleFold(const SlowFlowProblem& prob, double p_f,
                         const std::vector<CycleOnBranch>& leg_a,
                         const std::vector<CycleOnBranch>& leg_b);

}  // namespace metrosync::continuation
