// Part 6 of the validation (`metrosync validate`): the slow flow's bifurcations for the paper's
// families, by continuation (sim/analysis/continuation/): f4.3 in mu (identical metronomes) and
// f4.4 in metronome 2's detuning alpha. Every fold and Hopf point located on the branch of the
// family's locked state is checked by direct slow-flow runs on both sides of it (started on the
// locked state at the point, slightly perturbed: the state persists on one side and leaves on the
// other), and the same transition is looked for in the full model at epsilon = 0.073 and 0.02 by
// a bracket: the full model's regime from the rig's start on a grid of the parameter around the
// point, and the first pair of neighbours whose regimes differ.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "models/scaling.h"
#include "sim/analysis/validation/validation_catalogue.h"
#include "sim/analysis/validation/validation_runs.h"

namespace metrosync {

struct BifurcationFamilySpec {
  std::string name;      // "f4.4 in alpha"
  std::string scenario;  // the shipped scenario whose rig is varied, "f4.4-alpha4"
  std::string key;       // the rig key, for the report: "metronomes.1.alpha"
  std::function<void(ScaledParams&, double)> set;  // puts the parameter into the scaled rig
  double start = 0.0;                              // where the locked state is settled
  double lo = 0.0, hi = 0.0;                       // the continuation's range
  std::vector<double> full_epsilons;               // of the full-model brackets
  int full_points = 9;  // grid of the bracket: the point +- full_halfwidth
  double full_halfwidth = 0.3;
  std::string meaning;  // what the transition means for the paper's figures (report text)
};

// The paper's two families (quick: the brackets at epsilon = 0.073 only, on 5 points).
std::vector<BifurcationFamilySpec> paperBifurcationFamilies(bool quick);

struct SideCheck {  // a slow-flow run from the point's locked state at value + offset
  double value = 0.0;
  double distance = 0.0;  // envelopeDistance of the final state from the start
  bool persists = false;  // distance <= kPersistDistance
};

struct LocatedPoint {
  std::string type;  // fold | hopf
  double value = 0.0;
  std::vector<double> A, psi;
  std::string detail;
  // Checked where the state's stability changes at the point (a stable state is born, dies or
  // loses stability there); a point between two unstable states has nothing to persist.
  bool checked = false;
  SideCheck below, above;
  bool pass = false;  // checked: exactly one side persists; else true
};

struct FullBracket {
  double epsilon = 0.0;
  std::vector<double> values;
  std::vector<std::string> regimes;  // per value ("failed" for a run that stopped)
  double lo = std::numeric_limits<double>::quiet_NaN(), hi = lo;  // NaN: no change on the grid
};

struct BifurcationFamilyResult {
  BifurcationFamilySpec spec;
  std::string start;  // how the locked state was found, or why not
  std::vector<LocatedPoint> points;
  std::vector<std::vector<FullBracket>> full;  // per point, per epsilon
};

// A state persists when a run of kCheckTau from it, perturbed by kCheckPerturbation, ends within
// this distance of the point's state: the stable state 1% of the range away from a fold is
// O(sqrt(0.01)) ~ 0.1 from it, while a run that leaves ends on another state or at rest, O(1) away
// (amplitudes ~1-2). The same bound as kAgreeDistance (validation_measures.h).
constexpr double kPersistDistance = 0.25;

// Runs part 6 on the scenarios (which must include the families'). Full-model runs go through
// `engines.full_model`; `jobs` threads share them.
std::vector<BifurcationFamilyResult> runBifurcationFamilies(
    const std::vector<BifurcationFamilySpec>& families, const std::vector<Scenario>& scenarios,
    const ValidationEngines& engines, int jobs);

}  // namespace metrosync
