// What the validation found (sim/analysis/validation/validation.h), part by part: the runs, checks,
// errors and agreements that the report (tools/report/validation_report.h) writes.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sim/analysis/validation/validation_bifurcations.h"
#include "sim/analysis/validation/validation_checks.h"
#include "sim/analysis/validation/validation_experiments.h"
#include "sim/analysis/validation/validation_full_orbits.h"
#include "sim/analysis/validation/validation_measures.h"
#include "sim/analysis/validation/validation_plan.h"
#include "sim/analysis/validation/validation_runs.h"

namespace metrosync {

struct BetaRow {
  double s = 0.0;
  double beta1_closed = 0.0, beta2_closed = 0.0;
  DrivenCoulombMeasurement measured;
  double err1 = 0.0, err2 = 0.0;  // |measured - closed|
  bool pass = false;
};

struct ScenarioResult {  // part 2
  std::string name;
  ModelRun slow;
  std::vector<Check> checks;
  bool pass = false;
};

struct ConvergenceResult {  // part 3
  std::string name;
  std::vector<double> eps;
  std::vector<EnvelopeError> error;  // per eps
  double order = 0.0;                // fitted on max_distance
  std::vector<int> runs_complete;    // per eps: both models ran to the end (1)
  bool complete = true;
  bool pass = false;
};

struct RegimeComparison {  // part 4
  std::string name;
  double tau_end = 0.0;
  ModelRun slow;                 // at the rig's epsilon
  std::vector<ModelRun> full;    // per plan.regime_eps
  std::vector<double> distance;  // envelopeDistance of the final states, full vs slow
  std::vector<bool> agree;       // same regime (and a settled state within kAgreeDistance)
  // two identical metronomes (same nu, J, theta_c, no detuning): the distance with the full
  // model's metronomes exchanged (NaN otherwise), and whether the states agree that way
  std::vector<double> mirror_distance;
  std::vector<bool> mirror_agree;
};

struct FrictionSweepPoint {  // part 5: one friction value, both models
  double mu = 0.0, mu_bar = 0.0;
  ModelRun slow, full;
};

struct ValidationResults {
  ValidationPlan plan;
  std::vector<BetaRow> betas;
  std::vector<ScenarioResult> scenarios;
  std::vector<ConvergenceResult> convergence;
  std::vector<RegimeComparison> regimes;
  std::string sweep_scenario;
  double sweep_epsilon = 0.0, sweep_tau = 0.0, sweep_psi0 = 0.0;  // of the sweep's base rig
  std::vector<FrictionSweepPoint> sweep;
  std::vector<BifurcationFamilyResult> bifurcations;  // part 6
  std::optional<FullOrbitsResult> full_orbits;        // part 7
  std::optional<ExperimentsResult> experiments;       // part 8
  double wall_seconds = 0.0;

  int failedChecks() const;    // betas, paper regimes, convergence orders
  int incompleteRuns() const;  // runs of either model that stopped early
};

}  // namespace metrosync
