// A continuation of the slow flow as plain values: what `metrosync continue` writes
// (tools/report/continuation_report.h), in the rig's metronome numbering (1-based in names).
#pragma once

#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "sim/analysis/continuation/branch.h"
#include "sim/analysis/continuation/fold_curve.h"
#include "sim/analysis/continuation/slow_flow_cycles.h"
#include "sim/analysis/continuation/slow_flow_problem.h"

namespace metrosync::continuation {

struct ResultPoint {
  int branch = 0;
  double value = 0.0;       // the parameter
  std::vector<double> A;    // (N x 1)
  std::vector<double> psi;  // (N-1 x 1), phi_1 - phi_j in [-pi/2, 3 pi/2)
  double omega = 0.0;       // the locked state's rotation rate in slow time
  bool stable = false;
  double max_real = 0.0;  // largest real part of the eigenvalues
  // metronomes with the escapement on, "1 2" ("none"); a metronome on its threshold (a border
  // state, A_i = theta_c,i) as "2:0.47", its escapement working on that fraction of its swings
  std::string ticking;
  std::string platform;  // beta's regime: stuck (s <= 1), stick-slip (1 < s <= s_b), slip
  double s = 0.0;        // |Z| / mu
  std::vector<std::complex<double>> eigenvalues;
  // a border state (sim/analysis/continuation/border_states.h): the metronome on its threshold
  // (1-based) and the weight of its escapement's formula; 0 and NaN otherwise
  int on_threshold = 0;
  double weight = std::numeric_limits<double>::quiet_NaN();
};

struct ResultSpecial {
  ResultPoint at;
  std::string type;  // fold | hopf | branch | border
  std::string detail;
  double lyapunov = 0.0;  // hopf only (NaN when unknown)
  bool stability_changes = false;
};

struct ResultBranch {
  int id = 0;
  long points = 0;
  std::string end_backward, end_forward;
  bool max_points = false;  // an end was stopped by --max-points
  int neutral = 0;          // > 0: a neutral family (its extent in ContinuationResult::families)
};

// A neutral family's extent at one parameter value: the range of each amplitude and phase
// difference over its members (psi unwrapped about the representative's).
struct ResultFamilyPoint {
  double value = 0.0;
  std::vector<double> A_min, A_max, psi_min, psi_max;
  bool closed = false;  // every phase difference (the family closes on itself)
  std::string ends;     // what ends it on either side
};

struct ResultFamily {
  int id = 0;
  int branch = 0;   // its representative members in points
  int neutral = 0;  // its dimension (zero eigenvalues along it)
  std::string cause;
  std::vector<ResultFamilyPoint> points;
};

struct ContinuationResult {
  std::string param;  // the rig key
  double from = 0.0, to = 0.0;
  std::string start;  // how the start was found
  int metronomes = 0;
  std::vector<double> theta_c;  // (N x 1) at the start
  std::vector<ResultPoint> points;
  std::vector<ResultSpecial> special;
  std::vector<ResultBranch> branches;
  std::vector<ResultFamily> families;
  // the limit cycle born at each Hopf point (one per distinct Hopf point)
  std::vector<ResultCycle> cycles;
  int cycle_budget = 0;  // each cycle's point budget
  // --fold: the second key and the curve of each fold and Hopf point in (param, param2)
  std::string param2;
  std::vector<FoldCurve> fold_curves;
};

// Appends the branches (ids offset by the branches already in `out`) to `out`.
void appendBranches(const SlowFlowProblem& prob, const std::vector<Branch>& branches,
                    ContinuationResult& out);

}  // namespace metrosync::continuation
