// What `metrosync validate` runs (sim/analysis/validation/validation.h): the drive strengths,
// scenarios, epsilons and friction values of each part, the full plan or the quick one.
#pragma once

#include <string>
#include <vector>

#include "sim/analysis/validation/validation_bifurcations.h"

namespace metrosync {

struct ValidationPlan {
  bool quick = false;
  // part 1
  std::vector<double> beta_s;
  double beta_tol = 1e-7;
  // part 2: every shipped scenario with a PaperOutcome, at its shipped tau
  // part 3
  std::vector<std::string> convergence_scenarios;
  std::vector<double> convergence_eps = {0.04, 0.02, 0.01};
  double convergence_tau = 5.0;
  double order_lo = 0.7, order_hi = 1.3;
  // part 4; epsilon 0 stands for the rig's own epsilon
  std::vector<std::string> regime_scenarios;
  std::vector<double> regime_eps = {0.0, 0.02, 0.005};
  // part 5: the scenario's rig (its own epsilon and tau) with mu replaced
  std::string sweep_scenario = "experiment-low-friction-inphase";
  std::vector<double> sweep_mu;
  // ... refined: between neighbours whose labels differ in either model (sweepLabel) their
  // geometric mean is run, round after round, until such neighbours are within a ratio of
  // 1 + sweep_resolution (0: the grid alone), so that no window of a regime wider than that
  // between two points of different regimes goes unseen
  double sweep_resolution = 0.0;
  // part 6: the slow flow's bifurcations (sim/analysis/validation/validation_bifurcations.h)
  std::vector<BifurcationFamilySpec> bifurcations;
  // part 7: the full model's bifurcations (sim/analysis/validation/validation_full_orbits.h); on in
  // both of defaultValidationPlan's plans
  bool full_orbits = false;
  // part 8: the paper's experiments in each variant of the rig (validation_experiments.h); the
  // measured frequency the second variant's inertia is found from (section 3D)
  bool experiments = false;
  double measured_frequency_hz = 2.69;
};

// The full plan (`metrosync validate`) or the quick one (`--quick`).
ValidationPlan defaultValidationPlan(bool quick);

}  // namespace metrosync
