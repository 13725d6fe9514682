// The validation library's own pieces (sim/analysis/validation/validation.h,
// tools/report/validation_report.h) on inputs whose answers are known by construction: the order
// fit, the envelope distance and error, the rig at another epsilon, the agreement rule, the regime
// sequence, and the report (its numbers are the results' numbers).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/constants.h"
#include "fixtures.h"
#include "sim/analysis/validation/validation_parts.h"
#include "sim/engines/direct/direct_engine.h"
#include "tools/report/validation_report.h"

namespace metrosync {
namespace {

EnvelopeRow row(double tau, std::vector<double> A, std::vector<double> psi) {
  return {tau, std::move(A), std::move(psi)};
}

TEST(ValidationLibrary, FitOrderRecoversExactPowerLaws) {
  for (double p : {0.5, 1.0, 2.0}) {
    std::vector<double> x = {0.04, 0.02, 0.01}, y;
    for (double v : x) y.push_back(3.7 * std::pow(v, p));
    EXPECT_NEAR(fitOrder(x, y), p, 1e-12);
  }
  // least squares, not the end points: in log2 units x = 0..3, y = 0, 1, 2, 4 has slope
  // 6.5 / 5 = 1.3 (the end points alone would say 4/3)
  EXPECT_NEAR(fitOrder({1, 2, 4, 8}, {1, 2, 4, 16}), 1.3, 1e-12);
  EXPECT_THROW(fitOrder({1}, {1}), std::invalid_argument);
  EXPECT_THROW(fitOrder({1, 1}, {1, 2}), std::invalid_argument);
  EXPECT_THROW(fitOrder({1, 2}, {0, 2}), std::invalid_argument);
}

TEST(ValidationLibrary, EnvelopeDistanceWeighsPhaseByAmplitude) {
  // A_1 differs by 0.1, metronome 2 the same: 0.1
  EXPECT_NEAR(envelopeDistance(row(0, {2.0, 1.0}, {0.5}), row(0, {2.1, 1.0}, {0.5})), 0.1, 1e-15);
  // a phase error of pi at amplitude 1e-3 counts 2e-3, not pi
  EXPECT_NEAR(envelopeDistance(row(0, {2.0, 1e-3}, {0.0}), row(0, {2.0, 1e-3}, {kPi})), 2e-3,
              1e-15);
  // branches 2 pi apart are the same state
  EXPECT_NEAR(envelopeDistance(row(0, {2.0, 1.5}, {0.3}), row(0, {2.0, 1.5}, {0.3 + 2 * kPi})), 0.0,
              1e-12);
  // a small phase error dpsi at amplitude A: ~A dpsi
  EXPECT_NEAR(envelopeDistance(row(0, {2.0, 1.5}, {1.0}), row(0, {2.0, 1.5}, {1.001})), 1.5e-3,
              1e-8);
}

TEST(ValidationLibrary, EnvelopeErrorMatchesRowsOnTheGridAndStopsAtTauMax) {
  const double eps = 0.05;
  std::vector<EnvelopeRow> full, slow;
  for (long k = 0; k < 20; ++k) {
    const double tau = envelopeTau(eps, k);
    slow.push_back(row(tau, {2.0, 2.0}, {kPi}));
    // the full model lags by a tenth of a period here and there; its error grows with k
    full.push_back(row(tau + 1e-9, {2.0 + 0.01 * k, 2.0}, {kPi}));
  }
  full.erase(full.begin() + 3);  // a missing row is skipped, not mismatched
  const double tau_max = 0.5 * (envelopeTau(eps, 9) + envelopeTau(eps, 10));  // rows 0..9
  const EnvelopeError e = envelopeError(full, slow, eps, tau_max);
  EXPECT_EQ(e.rows, 9);
  EXPECT_NEAR(e.max_distance, 0.09, 1e-12);
  EXPECT_NEAR(e.tau_at_max, envelopeTau(eps, 9) + 1e-9, 1e-12);
  EXPECT_NEAR(e.max_dA, 0.09, 1e-12);
  EXPECT_EQ(e.max_dpsi, 0.0);
}

TEST(ValidationLibrary, RigAtEpsilonKeepsEveryScaledParameter) {
  for (const char* name : {"f4.4-alpha2", "experiment-high-friction-inphase"}) {
    SCOPED_TRACE(name);
    const ScaledParams p = testval::loadScenario(name).scaled;
    for (double eps : {0.04, 0.005}) {
      const ScaledParams q = computeScaled(rigAtEpsilon(p, name, eps, 7.0));
      // through the equivalent physical system and back: rounding, amplified by 1/eps in alpha
      EXPECT_NEAR(q.epsilon, eps, 1e-15);
      EXPECT_NEAR(q.tau_end, 7.0, 1e-12);
      EXPECT_NEAR(*q.friction.value("mu"), *p.friction.value("mu"), 1e-12);
      for (size_t i = 0; i < p.nu.size(); ++i) {
        EXPECT_NEAR(q.nu[i], p.nu[i], 1e-12);
        EXPECT_NEAR(q.J[i], p.J[i], 1e-12);
        EXPECT_NEAR(q.theta_c[i], p.theta_c[i], 1e-12);
        EXPECT_NEAR(q.alpha[i], p.alpha[i], 1e-9);
        EXPECT_NEAR(q.theta0[i], p.theta0[i], 1e-12);
        EXPECT_NEAR(q.thetadot0[i], p.thetadot0[i], 1e-12);
      }
    }
  }
}

ModelRun judged(Regime g, std::vector<double> A, std::vector<double> psi,
                const std::string& platform = "") {
  ModelRun m;
  m.report.complete = true;
  m.report.final_row = row(10, std::move(A), std::move(psi));
  m.verdict.regime = g;
  m.platform = platform;
  return m;
}

TEST(ValidationLibrary, AgreementNeedsTheSameRegimeAndForSettledStatesTheSameState) {
  const ModelRun a = judged(Regime::Antiphase, {2.9, 2.9}, {kPi});
  const ModelRun b = judged(Regime::Antiphase, {3.2, 2.2}, {3.0});
  EXPECT_TRUE(finalStatesAgree(a, a, 0.0));
  EXPECT_FALSE(finalStatesAgree(a, b, envelopeDistance(a.final(), b.final())));
  EXPECT_FALSE(finalStatesAgree(a, judged(Regime::InPhase, {2.9, 2.9}, {0}), 0.0));
  // death: nothing left to compare; drift: no state
  EXPECT_TRUE(finalStatesAgree(judged(Regime::Death, {0, 0}, {1}),
                               judged(Regime::Death, {0, 0}, {-2}), 5.0));
  ModelRun failed = a;
  failed.report.complete = false;
  failed.verdict.regime = Regime::Unknown;
  EXPECT_FALSE(finalStatesAgree(failed, a, 0.0));
}

TEST(ValidationLibrary, ExchangingIdenticalMetronomesIsASymmetry) {
  const EnvelopeRow a = row(3, {1.4, 0.6}, {-3.3});
  const EnvelopeRow b = exchangedPair(a);
  EXPECT_EQ(b.A, (std::vector<double>{0.6, 1.4}));
  EXPECT_EQ(b.psi, (std::vector<double>{3.3}));
  EXPECT_EQ(exchangedPair(b).A, a.A);
  // the suppressed one exchanged: far apart as they stand, equal once exchanged
  const EnvelopeRow c = row(3, {0.6, 1.4}, {3.3});
  EXPECT_GT(envelopeDistance(a, c), 0.5);
  EXPECT_NEAR(envelopeDistance(exchangedPair(a), c), 0.0, 1e-15);
  // identical only when nothing but the start differs
  EXPECT_TRUE(identicalPair(testval::loadScenario("f4.3-mu0.3").scaled));
  EXPECT_TRUE(identicalPair(testval::loadScenario("experiment-low-friction-antiphase").scaled));
  EXPECT_FALSE(identicalPair(testval::loadScenario("f4.4-alpha0.2").scaled));
}

TEST(ValidationLibrary, RegimeSequenceCollapsesAndMarksUncoupledStates) {
  std::vector<FrictionSweepPoint> sweep;
  auto add = [&](double mu, Regime g, const std::string& platform) {
    FrictionSweepPoint p;
    p.mu = mu;
    p.slow = judged(g, {2, 2}, {0}, platform);
    p.full = p.slow;
    sweep.push_back(p);
  };
  add(0.1, Regime::InPhase, "slipping");
  add(0.2, Regime::InPhase, "stick-slip");
  add(0.5, Regime::Suppression, "stick-slip");
  add(0.8, Regime::Death, "stuck");
  add(1.0, Regime::Death, "stuck");
  add(3.0, Regime::PhaseLocked, "stuck");
  const auto seq = regimeSequence(sweep, false);
  ASSERT_EQ(seq.size(), 4u);
  EXPECT_EQ(seq[0].label, "in-phase");
  EXPECT_EQ(seq[0].mu_from, 0.1);
  EXPECT_EQ(seq[0].mu_to, 0.2);
  EXPECT_EQ(seq[2].label, "death");  // dead over a still platform is just death
  EXPECT_EQ(seq[2].mu_to, 1.0);
  EXPECT_EQ(seq[3].label, "phase-locked, uncoupled");
}

// Part 5's refinement adds the geometric mean of neighbours whose labels differ in either model,
// while they are farther apart than the resolution; nothing between equal labels, nothing at
// resolution 0, and a stopped run ("failed") is a label of its own.
TEST(ValidationLibrary, SweepRefinementsBisectWhereEitherModelsLabelChanges) {
  std::vector<FrictionSweepPoint> sweep;
  auto add = [&](double mu, Regime slow, Regime full, const std::string& platform = "slipping") {
    FrictionSweepPoint p;
    p.mu = mu;
    p.slow = judged(slow, {2, 2}, {0}, platform);
    p.full = judged(full, {2, 2}, {0}, platform);
    sweep.push_back(p);
  };
  add(0.1, Regime::InPhase, Regime::InPhase);
  add(0.2, Regime::InPhase, Regime::InPhase);            // same as 0.1: nothing
  add(0.4, Regime::InPhase, Regime::Suppression);        // the full model changes: sqrt(0.08)
  add(0.404, Regime::Suppression, Regime::Suppression);  // the slow flow changes, 1% apart
  add(0.8, Regime::Death, Regime::Death);                // both change: sqrt(0.3232)
  add(1.0, Regime::Death, Regime::Death, "stuck");       // death is death over a still platform
  add(3.0, Regime::PhaseLocked, Regime::PhaseLocked, "stuck");  // alive and uncoupled
  const std::vector<double> mids = sweepRefinements(sweep, 0.02);
  ASSERT_EQ(mids.size(), 3u);
  EXPECT_DOUBLE_EQ(mids[0], std::sqrt(0.2 * 0.4));
  EXPECT_DOUBLE_EQ(mids[1], std::sqrt(0.404 * 0.8));
  EXPECT_DOUBLE_EQ(mids[2], std::sqrt(1.0 * 3.0));
  EXPECT_EQ(sweepRefinements(sweep, 0.005).size(), 4u);  // 0.4 and 0.404 now count too
  EXPECT_TRUE(sweepRefinements(sweep, 0.0).empty());
  sweep[1].full.report.complete = false;  // a stopped run differs from its neighbours
  EXPECT_EQ(sweepRefinements(sweep, 0.02).size(), 4u);
}

// The full plan's refinement on the experiment's in-phase rig between the grid's mu = 0.4
// (in-phase) and 0.5 (death in the full model): it finds the full model's suppression window
// (mu 0.47-0.505, issue 41, from runs at mu steps of 0.005) that the grid steps over, and leaves
// no two neighbours of different labels farther apart than the resolution.
TEST(ValidationLibrary, RefinedSweepFindsTheSuppressionWindowBetweenGridPoints) {
  ValidationPlan plan;
  plan.beta_s = {};
  plan.convergence_scenarios = {};
  plan.regime_scenarios = {};
  plan.sweep_mu = {0.4, 0.5};
  plan.sweep_resolution = 0.02;
  ValidationEngines direct = testval::engines();  // the direct engine: `validate`'s default
  direct.full_model = [](const Rig& rig, RunSink& sink) { return runDirectModel(rig, sink); };
  const ValidationResults r = runValidation(plan, testval::loadScenarios(), direct, {}, 2);
  ASSERT_GT(r.sweep.size(), 2u);
  EXPECT_EQ(r.sweep.front().mu, 0.4);
  EXPECT_EQ(r.sweep.back().mu, 0.5);
  bool window = false;
  for (size_t k = 0; k + 1 < r.sweep.size(); ++k) {
    const FrictionSweepPoint &a = r.sweep[k], &b = r.sweep[k + 1];
    EXPECT_LT(a.mu, b.mu);
    if (sweepLabel(a.full) != sweepLabel(b.full) || sweepLabel(a.slow) != sweepLabel(b.slow)) {
      EXPECT_LE(b.mu, a.mu * 1.02 * (1 + 1e-12)) << a.mu << " .. " << b.mu;
    }
  }
  for (const auto& p : r.sweep) window |= p.full.verdict.regime == Regime::Suppression;
  EXPECT_TRUE(window) << "no full-model suppression between mu = 0.4 and 0.5";
  const auto seq = regimeSequence(r.sweep, true);
  ASSERT_GE(seq.size(), 3u);
  EXPECT_EQ(seq.front().label, "in-phase");
  EXPECT_EQ(seq.back().label, "death");
  EXPECT_EQ(r.incompleteRuns(), 0);
}

// The report is made of the results: distinctive numbers put in come out in the tables, and the
// plots it links are only the ones written.
TEST(ValidationLibrary, ReportTablesCarryTheResultsNumbers) {
  ValidationResults r;
  r.plan = defaultValidationPlan(true);
  BetaRow b;
  b.s = 1.2345;
  b.beta1_closed = 0.0123456789;
  b.measured.beta1 = 0.0123456789;
  b.measured.periodic = true;
  b.pass = true;
  r.betas.push_back(b);
  ConvergenceResult c;
  c.name = "f4.2";
  c.eps = r.plan.convergence_eps;
  for (double e : c.eps) {
    EnvelopeError err;
    err.max_distance = 1.7 * e;
    c.error.push_back(err);
  }
  c.order = 0.987654;
  c.pass = true;
  r.convergence.push_back(c);
  r.wall_seconds = 42;
  ReportContext ctx{"metrosync validate --quick --out X", "yaml/rigs", "2000-01-01 00:00 UTC",
                    "direct"};
  const std::string md = validationReportMarkdown(r, ctx, {"convergence.png"});
  // the report says which engine ran the full model (validate's --engine)
  EXPECT_NE(md.find("The full model is the direct engine"), std::string::npos);
  EXPECT_EQ(validationJson(r, ctx)["engine"], "direct");
  EXPECT_NE(md.find("`metrosync validate --quick --out X`"), std::string::npos);
  EXPECT_NE(md.find("1.2345"), std::string::npos);
  EXPECT_NE(md.find("0.012345678900"), std::string::npos);
  EXPECT_NE(md.find("0.988"), std::string::npos);   // the order, 3 decimals
  EXPECT_NE(md.find("0.0680"), std::string::npos);  // 1.7 * 0.04
  EXPECT_NE(md.find("](convergence.png)"), std::string::npos);
  EXPECT_EQ(md.find("](betas.png)"), std::string::npos);  // not written, not linked
  for (const char* section : {"## Summary", "## 1.", "## 2.", "## 3."})
    EXPECT_NE(md.find(section), std::string::npos) << section;
}

// A tiny plan end to end through runValidation and writeValidationReport: every part runs, the
// files appear, and a failed check is counted.
TEST(ValidationLibrary, TinyPlanRunsEveryPartAndWritesTheReport) {
  ValidationPlan plan;
  plan.beta_s = {0.8, 1.5};
  plan.convergence_scenarios = {"f4.3-mu0.2"};
  plan.convergence_eps = {0.04, 0.02};
  plan.convergence_tau = 1.0;
  plan.regime_scenarios = {"f4.3-mu0.4"};
  plan.regime_eps = {0.0};
  plan.sweep_mu = {0.3};
  std::vector<Scenario> scenarios = testval::loadScenarios();
  // shorten what the tiny plan runs: the sweep's base rig and the regime window
  for (auto& sc : scenarios) {
    if (sc.spec.name == plan.sweep_scenario) sc.scaled.tau_end = 2.0;
    if (sc.spec.name == "f4.3-mu0.4") sc.spec.regime_tau = 30.0;
  }
  std::vector<std::string> lines;
  const ValidationResults r = runValidation(plan, scenarios, testval::engines(),
                                            [&](const std::string& l) { lines.push_back(l); });
  EXPECT_EQ(r.betas.size(), 2u);
  EXPECT_EQ(r.scenarios.size(), 8u);  // the paper's eight, always
  ASSERT_EQ(r.convergence.size(), 1u);
  ASSERT_EQ(r.regimes.size(), 1u);
  EXPECT_EQ(r.regimes[0].full.size(), 1u);
  EXPECT_EQ(r.regimes[0].full[0].epsilon, 0.073);  // the rig's own
  EXPECT_EQ(r.sweep.size(), 1u);
  EXPECT_EQ(r.incompleteRuns(), 0);
  for (const auto& b : r.betas) EXPECT_TRUE(b.pass) << "s = " << b.s;
  for (const auto& s : r.scenarios) EXPECT_TRUE(s.pass) << s.name;
  EXPECT_FALSE(lines.empty());
  // the slow flow's f4.3-mu0.4 dies by tau = 12; the full model at 0.073 too (a regime verdict
  // that both models give, from two independent codes)
  EXPECT_EQ(r.regimes[0].slow.verdict.regime, Regime::Death);

  const std::string dir = ::testing::TempDir() + "/metrosync_validation_tiny";
  std::filesystem::remove_all(dir);
  const OutputDir out(dir);
  const auto files = writeValidationReport(out, r, {"tiny", "yaml/rigs", "now", "direct"});
  EXPECT_TRUE(std::filesystem::exists(dir + "/report.md"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/summary.json"));
  std::ifstream in(dir + "/summary.json");
  std::stringstream ss;
  ss << in.rdbuf();
  const auto j = nlohmann::json::parse(ss.str());
  EXPECT_EQ(j["failed_checks"].get<int>(), r.failedChecks());
  EXPECT_EQ(j["betas"].size(), 2u);

  EXPECT_EQ(r.regimes[0].mirror_distance.size(), 1u);  // f4.3-mu0.4: identical metronomes
  EXPECT_TRUE(std::isfinite(r.regimes[0].mirror_distance[0]));

  // the failed checks are the failing betas, paper checks and convergence orders
  int failing = 0;
  for (const auto& b : r.betas) failing += !b.pass;
  for (const auto& s : r.scenarios)
    for (const auto& c : s.checks) failing += !c.pass;
  for (const auto& c : r.convergence) failing += !c.pass;
  EXPECT_EQ(r.failedChecks(), failing);
  ValidationResults flipped = r;
  flipped.convergence[0].pass = !r.convergence[0].pass;
  EXPECT_EQ(std::abs(flipped.failedChecks() - r.failedChecks()), 1);
}

}  // namespace
}  // namespace metrosync

namespace metrosync {
namespace {

// The runs are independent and each builds its own Simbody system: two threads give the very
// same numbers as one (no shared state between the engines' runs).
TEST(ValidationLibrary, ResultsDoNotDependOnTheNumberOfJobs) {
  ValidationPlan plan;
  plan.beta_s = {1.5, 3.0};
  plan.convergence_scenarios = {"f4.2", "experiment-high-friction-inphase"};
  plan.convergence_eps = {0.04, 0.02};
  plan.convergence_tau = 1.0;
  plan.regime_scenarios = {};
  plan.sweep_mu = {};
  const std::vector<Scenario> scenarios = testval::loadScenarios();
  const ValidationResults one = runValidation(plan, scenarios, testval::engines(), {}, 1);
  const ValidationResults two = runValidation(plan, scenarios, testval::engines(), {}, 2);
  ASSERT_EQ(one.betas.size(), two.betas.size());
  for (size_t k = 0; k < one.betas.size(); ++k) {
    EXPECT_EQ(one.betas[k].measured.beta1, two.betas[k].measured.beta1);
    EXPECT_EQ(one.betas[k].measured.beta2, two.betas[k].measured.beta2);
  }
  ASSERT_EQ(one.convergence.size(), two.convergence.size());
  for (size_t c = 0; c < one.convergence.size(); ++c)
    for (size_t k = 0; k < one.convergence[c].error.size(); ++k)
      EXPECT_EQ(one.convergence[c].error[k].max_distance, two.convergence[c].error[k].max_distance);
}

}  // namespace
}  // namespace metrosync
