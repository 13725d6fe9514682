// Validation of the full model against the asymptotics (the slow flow e3.1a-c and its closed
// forms), behind `metrosync validate` and tests/validation. Its parts:
//   1. betas        beta1, beta2 (eq. d2) against the full model's own Coulomb element, driven by
//                   B sin t to its periodic steady state (contact/simbody/driven_coulomb.h)
//   2. scenarios    the paper's eight simulations (section 4) from the slow flow, with the regimes
//                   the paper describes
//   3. convergence  the full model at epsilon = 0.04, 0.02, 0.01 against the slow flow over
//                   tau in [0, 5]: max envelope error and its order in epsilon (theory: 1)
//   4. regimes      the final regime of each scenario from the full model at the rig's epsilon,
//                   0.02 and 0.005 next to the slow flow's: where the asymptotics fail
//   5. sweep        the experiment's regime sequence over mu (figure exp1, right panel), refined
//                   where the regime changes
//   (6, 7: the bifurcations of both models; 8: the paper's experiments in each variant of the
//   rig, validation_experiments.h)
// Core code: the engines that need Simbody (the full model, the Coulomb-element harness) come in
// as functions and the rigs come in loaded, so that sim/ depends on neither Simbody nor YAML.
// The pieces, one job per file (this header includes them all):
//   validation_catalogue  the shipped scenarios, what the paper says of each, rigAtEpsilon
//   validation_runs       one run of either model (ModelRun), the engines as functions
//   validation_measures   envelope distances and errors, orders of convergence, agreement
//   validation_checks     the paper's statements checked on a slow-flow run (part 2)
//   validation_plan       what each part runs, full or quick; validation_results what it found
//   validation_parts      the runners of parts 1-5; validation_progress their progress lines
//   validation_bifurcations, validation_full_orbits  parts 6 and 7
//   validation_experiments  part 8
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sim/analysis/validation/validation_bifurcations.h"
#include "sim/analysis/validation/validation_catalogue.h"
#include "sim/analysis/validation/validation_checks.h"
#include "sim/analysis/validation/validation_experiments.h"
#include "sim/analysis/validation/validation_full_orbits.h"
#include "sim/analysis/validation/validation_measures.h"
#include "sim/analysis/validation/validation_plan.h"
#include "sim/analysis/validation/validation_results.h"
#include "sim/analysis/validation/validation_runs.h"

namespace metrosync {

// Runs the plan on the scenarios (which must include every one the plan names). `progress`
// receives one line per run (from one thread at a time). The runs are independent: `jobs`
// threads share them, longest first; the results do not depend on jobs.
ValidationResults runValidation(const ValidationPlan& plan, const std::vector<Scenario>& scenarios,
                                const ValidationEngines& engines,
                                const std::function<void(const std::string&)>& progress = {},
                                int jobs = 1);

}  // namespace metrosync
