// The slow flow's continuation as `metrosync continue` runs it (and the Python module's
// continue_, and sweep --boundaries): from one start state or from every locked state Newton
// finds at the start value and the start state (--all), each branch once and each bifurcation once
// (sim/analysis/continuation/merge.h), the limit cycle born at each distinct Hopf point, and with a
// second key the curve of each distinct fold and Hopf point in the plane of the two keys. Results
// as values (result.h); the command line and the files are tools/.
#pragma once

#include <complex>
#include <stdexcept>
#include <vector>

#include "sim/analysis/continuation/fold_curve.h"
#include "sim/analysis/continuation/result.h"

namespace metrosync::continuation {

struct SlowFlowContinuationSpec {
  ParamsAt params;  // the slow flow's parameters at KEY = p
  double from = 0.0, to = 0.0;
  ContinuationSettings settings;  // of the branches (range, p_scale, steps, max points)
  // The start state (N x 1 complex amplitudes at `from`); empty: every locked state (--all).
  std::vector<std::complex<double>> start;
  // --all: every locked state Newton finds from a grid of seeds, and `start` first when it is
  // given (the rig's own start settled: a grid of seeds can miss the rig's own attractor)
  bool all = false;
  bool cycles = true;    // follow the limit cycle of each distinct Hopf point
  int cycle_points = 0;  // each cycle's point budget (0: settings.max_points)
  // The second key (--fold): its parameters at (KEY, KEY2) = (p1, p2); empty: no curves.
  ParamsAt2 params2;
  double from2 = 0.0, to2 = 0.0;
  ContinuationSettings settings2;  // of the curves, in KEY2
  P1Range range1;                  // KEY's range for the curves (sweep --boundaries: the map's)
  // curves already found (another row of a map): a seed on one of them is not followed again
  std::vector<FoldCurve> known_curves;
  // threads for --all's seeds and branches (0: one per hardware thread); the result is the same
  // on any number
  int jobs = 0;
};

// Bad input (a start Newton cannot converge from, no locked state at all for --all) throws this.
struct NoLockedState : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// The branches, special points, families and cycles; with params2 also fold_curves (param2,
// param, start and the rig's names are the caller's to fill in).
ContinuationResult continueSlowFlow(const SlowFlowContinuationSpec& spec);

}  // namespace metrosync::continuation
