#include "sim/analysis/validation/validation_parts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/number_text.h"
#include "contact/averaged_response.h"
#include "contact/law_registry.h"
#include "sim/analysis/compare.h"
#include "sim/parallel/worker_pool.h"

namespace metrosync {

// Part 1: betas against the Coulomb element.
void runBetas(const ValidationPlan& plan, const ValidationEngines& engines, ValidationLog& log,
              int jobs, ValidationResults& res) {
  res.betas.resize(plan.beta_s.size());
  parallelFor(static_cast<long>(plan.beta_s.size()), jobs, [&](long k) {
    BetaRow& row = res.betas[k];
    const double s = plan.beta_s[k];
    row.s = s;
    row.beta1_closed = coulombBeta1(s);
    row.beta2_closed = coulombBeta2(s);
    row.measured = engines.coulomb_probe(s);
    row.err1 = std::abs(row.measured.beta1 - row.beta1_closed);
    row.err2 = std::abs(row.measured.beta2 - row.beta2_closed);
    row.pass = row.measured.periodic && row.err1 <= plan.beta_tol && row.err2 <= plan.beta_tol;
    log.say("betas s = " + numberText(s, 9) +
            ": |d beta1| = " + numberText(row.err1, 1, Notation::Scientific) + ", |d beta2| = " +
            numberText(row.err2, 1, Notation::Scientific) + (row.pass ? "" : "  FAIL"));
  });
}

// Part 2: the paper's scenarios from the slow flow, at their shipped epsilon and tau (cheap).
void runPaperScenarios(const std::vector<Scenario>& scenarios, ValidationLog& log,
                       ValidationResults& res) {
  for (const auto& sc : scenarios) {
    if (sc.spec.outcome == PaperOutcome::None) continue;
    ScenarioResult r;
    r.name = sc.spec.name;
    r.slow = runSlowModel(sc.scaled, sc.scaled.epsilon, sc.scaled.tau_end);
    r.checks = paperChecks(sc.spec.outcome, r.slow, sc.scaled);
    r.pass = r.slow.report.complete &&
             std::all_of(r.checks.begin(), r.checks.end(), [](const Check& c) { return c.pass; });
    log.say("paper " + r.name + ": slow flow " + toString(r.slow.verdict.regime) +
            (r.pass ? "" : "  FAIL"));
    res.scenarios.push_back(std::move(r));
  }
}

// Part 3: convergence in epsilon over tau in [0, convergence_tau].
void queueConvergence(const ValidationPlan& plan, const std::vector<Scenario>& scenarios,
                      const ValidationEngines& engines, ValidationLog& log, ValidationResults& res,
                      std::vector<ValidationTask>& tasks) {
  res.convergence.resize(plan.convergence_scenarios.size());
  for (size_t c = 0; c < plan.convergence_scenarios.size(); ++c) {
    const Scenario& sc = findScenario(scenarios, plan.convergence_scenarios[c]);
    ConvergenceResult& cv = res.convergence[c];
    cv.name = sc.spec.name;
    cv.eps = plan.convergence_eps;
    cv.error.resize(cv.eps.size());
    cv.runs_complete.assign(cv.eps.size(), 0);
    for (size_t k = 0; k < cv.eps.size(); ++k)
      tasks.push_back(
          {plan.convergence_tau / cv.eps[k], [&res, &plan, &engines, &log, scp = &sc, c, k] {
             ConvergenceResult& cv2 = res.convergence[c];
             const double eps = cv2.eps[k], tau = plan.convergence_tau;
             const ModelRun slow = runSlowModel(scp->scaled, eps, tau);
             const ModelRun full = runFullModelAt(engines, scp->scaled, cv2.name, eps, tau);
             cv2.runs_complete[k] = slow.report.complete && full.report.complete;
             cv2.error[k] = envelopeError(full.envelope, slow.envelope, eps, tau);
             log.say("convergence " + cv2.name + " eps = " + numberText(eps) + ": error " +
                     numberText(cv2.error[k].max_distance, 3, Notation::Scientific) + " (" +
                     numberText(full.report.wall_seconds, 1, Notation::Fixed) + " s)");
           }});
  }
}

// Part 4: final regimes, the full model at several epsilons against the slow flow.
void queueRegimes(const ValidationPlan& plan, const std::vector<Scenario>& scenarios,
                  const ValidationEngines& engines, ValidationLog& log, ValidationResults& res,
                  std::vector<ValidationTask>& tasks) {
  res.regimes.resize(plan.regime_scenarios.size());
  for (size_t c = 0; c < plan.regime_scenarios.size(); ++c) {
    const Scenario& sc = findScenario(scenarios, plan.regime_scenarios[c]);
    RegimeComparison& rc = res.regimes[c];
    rc.name = sc.spec.name;
    rc.tau_end = sc.spec.regime_tau;
    rc.slow = runSlowModel(sc.scaled, sc.scaled.epsilon, rc.tau_end);
    log.run("regimes " + rc.name + " slow", rc.slow);
    rc.full.resize(plan.regime_eps.size());
    for (size_t k = 0; k < plan.regime_eps.size(); ++k) {
      const double eps = plan.regime_eps[k] > 0 ? plan.regime_eps[k] : sc.scaled.epsilon;
      tasks.push_back({rc.tau_end / eps, [&res, &engines, &log, scp = &sc, c, k, eps] {
                         RegimeComparison& rc2 = res.regimes[c];
                         rc2.full[k] =
                             runFullModelAt(engines, scp->scaled, rc2.name, eps, rc2.tau_end);
                         log.run("regimes " + rc2.name + " full eps = " + numberText(eps, 4) +
                                     " tau = " + numberText(rc2.tau_end),
                                 rc2.full[k]);
                       }});
    }
  }
}

// Part 5: the experiment's regime sequence over mu, both models at the rig's epsilon.
void queueMuSweep(const ValidationPlan& plan, const std::vector<Scenario>& scenarios,
                  const ValidationEngines& engines, ValidationLog& log, ValidationResults& res,
                  std::vector<ValidationTask>& tasks) {
  if (plan.sweep_mu.empty()) return;
  const Scenario& sc = findScenario(scenarios, plan.sweep_scenario);
  res.sweep_scenario = plan.sweep_scenario;
  res.sweep_epsilon = sc.scaled.epsilon;
  res.sweep_tau = sc.scaled.tau_end;
  const ScaledParams& b = sc.scaled;
  if (b.theta0.size() >= 2)
    res.sweep_psi0 =
        wrapToPi(std::atan2(b.theta0[0], b.thetadot0[0]) - std::atan2(b.theta0[1], b.thetadot0[1]));
  res.sweep.resize(plan.sweep_mu.size());
  for (size_t k = 0; k < plan.sweep_mu.size(); ++k) {
    tasks.push_back({b.tau_end / b.epsilon, [&res, &plan, &engines, &log, scp = &sc, k] {
                       res.sweep[k] = runSweepPoint(*scp, plan.sweep_mu[k], engines, log);
                     }});
  }
}

// One friction value of part 5: the scenario's rig with mu replaced, both models.
FrictionSweepPoint runSweepPoint(const Scenario& sc, double mu, const ValidationEngines& engines,
                                 ValidationLog& log) {
  FrictionSweepPoint pt;
  ScaledParams q = sc.scaled;
  q.friction = FrictionLaw::coulomb(mu);
  pt.mu = mu;
  pt.mu_bar = pt.mu * std::pow(q.epsilon, 1.5);
  pt.slow = runSlowModel(q, q.epsilon, q.tau_end);
  pt.full =
      runFullModelAt(engines, q, sc.spec.name + "-mu" + numberText(pt.mu), q.epsilon, q.tau_end);
  log.run("sweep mu = " + numberText(pt.mu) + " slow", pt.slow);
  log.run("sweep mu = " + numberText(pt.mu) + " full", pt.full);
  return pt;
}

std::vector<double> sweepRefinements(const std::vector<FrictionSweepPoint>& sweep,
                                     double resolution) {
  std::vector<double> mids;
  if (!(resolution > 0)) return mids;
  for (size_t k = 0; k + 1 < sweep.size(); ++k) {
    const FrictionSweepPoint &a = sweep[k], &b = sweep[k + 1];
    const bool differ =
        sweepLabel(a.slow) != sweepLabel(b.slow) || sweepLabel(a.full) != sweepLabel(b.full);
    if (differ && a.mu > 0 && b.mu > a.mu * (1 + resolution))
      mids.push_back(std::sqrt(a.mu * b.mu));
  }
  return mids;
}

void refineMuSweep(const ValidationPlan& plan, const std::vector<Scenario>& scenarios,
                   const ValidationEngines& engines, ValidationLog& log, ValidationResults& res,
                   int jobs) {
  if (res.sweep.empty() || !(plan.sweep_resolution > 0)) return;
  const Scenario& sc = findScenario(scenarios, plan.sweep_scenario);
  auto byMu = [](const FrictionSweepPoint& a, const FrictionSweepPoint& b) { return a.mu < b.mu; };
  std::sort(res.sweep.begin(), res.sweep.end(), byMu);
  for (int round = 0; round < kMaxSweepRefinements; ++round) {
    const std::vector<double> mids = sweepRefinements(res.sweep, plan.sweep_resolution);
    if (mids.empty()) return;
    log.say("sweep: " + std::to_string(mids.size()) + " friction values between regimes");
    std::vector<FrictionSweepPoint> added(mids.size());
    parallelFor(static_cast<long>(mids.size()), jobs,
                [&](long k) { added[k] = runSweepPoint(sc, mids[k], engines, log); });
    res.sweep.insert(res.sweep.end(), added.begin(), added.end());
    std::sort(res.sweep.begin(), res.sweep.end(), byMu);
  }
}

// Part 3 once every run is in: the order of convergence and its check.
void finishConvergence(const ValidationPlan& plan, ValidationLog& log, ValidationResults& res) {
  for (auto& cv : res.convergence) {
    cv.complete =
        std::all_of(cv.runs_complete.begin(), cv.runs_complete.end(), [](int b) { return b != 0; });
    std::vector<double> errs;
    for (const auto& e : cv.error) errs.push_back(e.max_distance);
    const bool positive = std::all_of(errs.begin(), errs.end(), [](double e) { return e > 0; });
    cv.order = positive && errs.size() >= 2 ? fitOrder(cv.eps, errs)
                                            : std::numeric_limits<double>::quiet_NaN();
    cv.pass = cv.complete && cv.order >= plan.order_lo && cv.order <= plan.order_hi;
    log.say("convergence " + cv.name + ": order " + numberText(cv.order, 3, Notation::Fixed) +
            (cv.pass ? "" : "  FAIL"));
  }
}

// Part 4 once every run is in: the distances of the final states, as run and exchanged.
void finishRegimes(const std::vector<Scenario>& scenarios, ValidationResults& res) {
  for (auto& rc : res.regimes) {
    const bool identical = identicalPair(findScenario(scenarios, rc.name).scaled);
    for (const ModelRun& full : rc.full) {
      const double d = envelopeDistance(full.final(), rc.slow.final());
      rc.distance.push_back(d);
      rc.agree.push_back(finalStatesAgree(full, rc.slow, d));
      const double dm = identical && full.final().A.size() == 2
                            ? envelopeDistance(exchangedPair(full.final()), rc.slow.final())
                            : std::numeric_limits<double>::quiet_NaN();
      rc.mirror_distance.push_back(dm);
      rc.mirror_agree.push_back(!rc.agree.back() && std::isfinite(dm) &&
                                finalStatesAgree(full, rc.slow, dm));
    }
  }
}

}  // namespace metrosync
