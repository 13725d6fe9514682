// The slow flow's limit cycles born at its Hopf points (limit_cycle.h on the reduced polar flow of
// the Hopf point's region), as plain values in the rig's numbering: a periodic orbit of the reduced
// flow is a state whose amplitudes and phase differences oscillate with the cycle's period
// (quasi-periodic metronomes: the modulation of the locked state born at the Hopf point).
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "sim/analysis/continuation/branch.h"
#include "sim/analysis/continuation/slow_flow_problem.h"

namespace metrosync::continuation {

struct ResultCyclePoint {
  double value = 0.0;                // the parameter
  double period = 0.0;               // in slow time tau
  std::vector<double> A0, psi0;      // a state on the cycle (its point on the shooting's section)
  std::vector<double> A_min, A_max;  // (N x 1) over the orbit
  std::vector<double> psi_min, psi_max;  // (N-1 x 1) over the orbit, psi in [-pi/2, 3 pi/2)
  std::vector<std::complex<double>> multipliers;  // Floquet multipliers, the trivial one included
  double max_multiplier = 0.0;                    // largest |multiplier| but the trivial one
  bool stable = false;
};

// A fold of cycles (two cycles, one stable, meet and vanish), checked by runs of the slow flow
// (sim/analysis/continuation/cycle_fold_check.h).
struct ResultCycleFold {
  ResultCyclePoint at;
  bool confirmed = false;  // a run stays on the stable cycle beside it and leaves beyond it
  std::string check;       // what the runs did, in words
};

struct ResultCycle {
  int id = 0;
  double hopf_value = 0.0;               // the parameter at the Hopf point the cycle is born at
  double frequency = 0.0;                // w of the Hopf pair: the period there is 2 pi / w
  std::vector<ResultCyclePoint> points;  // from the Hopf point outwards
  std::string end;
  bool max_points = false;  // stopped by its point budget
  bool into_hopf = false;   // it ended on a Hopf point (at its last point's parameter)
  std::vector<ResultCycleFold> folds;
  std::vector<std::string> changes;  // other changes of the cycle's stability, in words
};

// The cycle born at `hopf` (a Hopf point of prob's branch) over [s.p_min, s.p_max]; a Hopf point
// where an amplitude is 0 (the polar flow is singular there) gives an empty cycle with the reason.
ResultCycle followSlowFlowCycle(const SlowFlowProblem& prob, const BranchPoint& hopf,
                                const ContinuationSettings& s);

}  // namespace metrosync::continuation
