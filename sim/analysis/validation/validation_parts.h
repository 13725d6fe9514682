// The runners of parts 1-5 of the validation (sim/analysis/validation/validation.h), for
// runValidation: parts 1 and 2 run at once; the full-model runs of parts 3-5 are queued as tasks
// for one pool (longest first) and finished once every run is in.
#pragma once

#include <functional>
#include <vector>

#include "sim/analysis/validation/validation_catalogue.h"
#include "sim/analysis/validation/validation_plan.h"
#include "sim/analysis/validation/validation_progress.h"
#include "sim/analysis/validation/validation_results.h"
#include "sim/analysis/validation/validation_runs.h"

namespace metrosync {

// A full-model run of parts 3-5, queued so that one pool runs them longest (tau / epsilon) first.
struct ValidationTask {
  double cost;
  std::function<void()> run;
};

// Part 1: betas against the Coulomb element.
void runBetas(const ValidationPlan& plan, const ValidationEngines& engines, ValidationLog& log,
              int jobs, ValidationResults& res);
// Part 2: the paper's scenarios from the slow flow, at their shipped epsilon and tau (cheap).
void runPaperScenarios(const std::vector<Scenario>& scenarios, ValidationLog& log,
                       ValidationResults& res);
// Parts 3-5: their full-model runs (and the slow flow's next to them) as tasks.
void queueConvergence(const ValidationPlan& plan, const std::vector<Scenario>& scenarios,
                      const ValidationEngines& engines, ValidationLog& log, ValidationResults& res,
                      std::vector<ValidationTask>& tasks);
void queueRegimes(const ValidationPlan& plan, const std::vector<Scenario>& scenarios,
                  const ValidationEngines& engines, ValidationLog& log, ValidationResults& res,
                  std::vector<ValidationTask>& tasks);
void queueMuSweep(const ValidationPlan& plan, const std::vector<Scenario>& scenarios,
                  const ValidationEngines& engines, ValidationLog& log, ValidationResults& res,
                  std::vector<ValidationTask>& tasks);
// One friction value of part 5 (what queueMuSweep's tasks run).
FrictionSweepPoint runSweepPoint(const Scenario& sc, double mu, const ValidationEngines& engines,
                                 ValidationLog& log);
// Part 5's next friction values: the geometric mean of each pair of neighbours (the sweep in
// order of mu) whose labels differ in either model (sweepLabel) and whose ratio exceeds
// 1 + resolution; none for resolution 0.
std::vector<double> sweepRefinements(const std::vector<FrictionSweepPoint>& sweep,
                                     double resolution);
// Part 5 once the grid is in: the sweep put in order of mu, then rounds of sweepRefinements run on
// the pool and merged in, until none is left (plan.sweep_resolution) or after
// kMaxSweepRefinements rounds (from a grid step of 1.5x to 1.02x takes 5).
constexpr int kMaxSweepRefinements = 8;
void refineMuSweep(const ValidationPlan& plan, const std::vector<Scenario>& scenarios,
                   const ValidationEngines& engines, ValidationLog& log, ValidationResults& res,
                   int jobs);
// Parts 3 and 4 once every run is in.
void finishConvergence(const ValidationPlan& plan, ValidationLog& log, ValidationResults& res);
void finishRegimes(const std::vector<Scenario>& scenarios, ValidationResults& res);

}  // namespace metrosync
