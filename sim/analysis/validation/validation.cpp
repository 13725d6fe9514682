#include "sim/analysis/validation/validation.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <numeric>

#include "sim/analysis/validation/validation_parts.h"
#include "sim/parallel/worker_pool.h"

namespace metrosync {

using Clock = std::chrono::steady_clock;

ValidationResults runValidation(const ValidationPlan& plan, const std::vector<Scenario>& scenarios,
                                const ValidationEngines& engines,
                                const std::function<void(const std::string&)>& progress, int jobs) {
  const Clock::time_point t0 = Clock::now();
  ValidationLog log(progress);
  ValidationResults res;
  res.plan = plan;
  runBetas(plan, engines, log, jobs, res);
  runPaperScenarios(scenarios, log, res);

  // 3-5: every full-model run is a task of one pool, the longest first; the slow flow runs
  // alongside (cheap)
  std::vector<ValidationTask> tasks;
  queueConvergence(plan, scenarios, engines, log, res, tasks);
  queueRegimes(plan, scenarios, engines, log, res, tasks);
  queueMuSweep(plan, scenarios, engines, log, res, tasks);
  std::vector<size_t> order(tasks.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return tasks[a].cost > tasks[b].cost; });
  // the pool (sim/parallel/worker_pool.h): each thread takes the next task when free, so the
  // longest, listed first, balance best
  parallelFor(static_cast<long>(order.size()), jobs, [&](long k) { tasks[order[k]].run(); });

  refineMuSweep(plan, scenarios, engines, log, res, jobs);
  finishConvergence(plan, log, res);
  finishRegimes(scenarios, res);
  if (!plan.bifurcations.empty()) {
    log.say("bifurcations of the slow flow (continuation, slow-flow checks, full-model brackets)");
    res.bifurcations = runBifurcationFamilies(plan.bifurcations, scenarios, engines, jobs);
  }
  if (plan.full_orbits) {
    log.say("bifurcations of the full model (periodic orbits, continuation at several epsilon)");
    res.full_orbits = runFullOrbitBifurcations(plan.quick, scenarios, engines, jobs);
  }
  if (plan.experiments && engines.load_rig) {
    log.say("the paper's experiments (fig. exp1-exp3) in each variant of the rig");
    try {
      res.experiments = runExperiments(plan.measured_frequency_hz, scenarios, engines, log, jobs);
    } catch (const std::exception& e) {  // a run of one metronome stopped: said, counted
      res.experiments = ExperimentsResult{};
      res.experiments->failure = e.what();
      log.say("experiments: FAILED - " + res.experiments->failure);
    }
  }
  res.wall_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return res;
}

}  // namespace metrosync
