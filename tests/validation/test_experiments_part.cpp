// Part 8 of the validation (sim/analysis/validation/validation_experiments.h): its clocks on
// envelopes whose answers are known by construction, the inertia search against the pendulum's
// small-angle closed form, and the part on the shipped rigs (direct engine).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "base/constants.h"
#include "fixtures.h"
#include "sim/analysis/validation/validation_experiments.h"
#include "sim/engines/direct/direct_engine.h"
#include "tools/report/validation_report.h"

namespace metrosync {
namespace {

ValidationEngines directEngines() {
  ValidationEngines e = testval::engines();
  e.full_model = [](const Rig& rig, RunSink& sink) { return runDirectModel(rig, sink); };
  return e;
}

// A run whose envelope rows are tau = 0, 1, ..., 9 with the given amplitudes and phase.
ModelRun envelopeRun(const std::vector<double>& A1, const std::vector<double>& A2,
                     const std::vector<double>& psi) {
  ModelRun run;
  run.epsilon = 0.05;
  run.time_scale_s = 0.02;  // a tau of 1 is 1 / 0.05 * 0.02 = 0.4 s
  run.theta_c = {0.9, 0.9};
  run.report.complete = true;
  for (size_t k = 0; k < psi.size(); ++k)
    run.envelope.push_back({static_cast<double>(k), {A1[k], A2[k]}, {psi[k]}});
  return run;
}

TEST(ValidationExperiments, ClocksReadTheEnvelope) {
  const auto& exps = paperExperiments();
  ASSERT_EQ(exps.size(), 4u);
  const ExperimentSpec& exp2 = exps[0];
  const ExperimentSpec& exp3 = exps[1];
  ASSERT_EQ(exp2.clock, ExperimentClock::LeavesAntiphase);
  ASSERT_EQ(exp3.clock, ExperimentClock::Dies);
  const std::vector<double> alive(10, 2.0);
  // psi near pi (either side of it, and 2 pi away) until tau = 6, then past 0.5 rad from it
  const ModelRun leaves =
      envelopeRun(alive, alive,
                  {kPi, kPi + 0.4, -kPi - 0.3, 3 * kPi - 0.2, kPi, kPi, kPi + 0.6, 0.2, 0.0, 0.0});
  EXPECT_NEAR(experimentClock(exp2, leaves), 6 * 0.4, 1e-12);
  const ModelRun stays = envelopeRun(alive, alive, std::vector<double>(10, kPi - 0.45));
  EXPECT_TRUE(std::isnan(experimentClock(exp2, stays)));
  // both below theta_c = 0.9 for good from tau = 7 on (metronome 2 below from 4, 1 recovers once)
  const ModelRun dies =
      envelopeRun({2, 2, 2, 0.8, 1.0, 0.95, 0.91, 0.5, 0.1, 0.0},
                  {2, 2, 1, 0.5, 0.4, 0.3, 0.2, 0.1, 0.0, 0.0}, std::vector<double>(10, 0.0));
  EXPECT_NEAR(experimentClock(exp3, dies), 7 * 0.4, 1e-12);
  EXPECT_TRUE(std::isnan(experimentClock(exp3, stays)));
  // the judgement: the regime, and the clock within a factor of 2 of the paper's 10 s / 20 s
  ModelRun late = leaves;
  late.verdict.regime = Regime::InPhase;
  late.time_scale_s = 0.02 * 10.0 / 2.4;  // leaves at exactly 10 s
  EXPECT_TRUE(judgeExperiment(exp2, "v", late).reproduces());
  late.time_scale_s *= 2.1;  // 21 s: more than twice the paper's
  EXPECT_FALSE(judgeExperiment(exp2, "v", late).clock_ok);
  late.verdict.regime = Regime::Antiphase;
  EXPECT_FALSE(judgeExperiment(exp2, "v", late).regime_ok);
  ModelRun stays_in = stays;
  stays_in.verdict.regime = Regime::Antiphase;
  EXPECT_TRUE(judgeExperiment(exps[2], "v", stays_in).reproduces());  // no clock to meet
}

// Without its escapement (started at 0.01 rad, below theta_c) and damping (1e-9 1/s), the metronome
// is a pendulum on a bolted board: f = sqrt(m g L / I) / 2 pi to within A^2 / 16 = 6e-6. The
// search must find that inertia for 2 Hz from the shipped one.
TEST(ValidationExperiments, InertiaSearchMatchesThePendulumsClosedForm) {
  const ValidationEngines engines = directEngines();
  const std::string file =
      findScenario(testval::loadScenarios(), paperExperiments()[0].scenario).spec.file;
  const std::vector<std::string> free = {"metronomes.0.pendulum.decay_rate=1e-9",
                                         "metronomes.0.start.angle=0.01",
                                         "metronomes.0.start.rate=0"};
  const Rig rig = engines.load_rig(file, {});
  const MetronomeSpec& m = rig.metronomes[0];
  const double mgL = m.pendulum_mass_kg * rig.gravity_m_s2 * m.length_m;
  const double hz = 2.0;
  const InertiaSearch search = inertiaForFrequency(engines, file, free, m.inertia_kgm2, hz);
  const double reached = search.hz, inertia = search.inertia;
  const double closed = mgL / std::pow(2 * kPi * hz, 2);
  EXPECT_NEAR(reached, hz, 1e-4 * hz);
  EXPECT_NEAR(inertia / closed, 1.0, 3e-4) << inertia << " against " << closed;
  // and the shipped inertia's own frequency, m L^2, from the same closed form
  EXPECT_NEAR(oneMetronomeFrequency(engines, file, free),
              std::sqrt(mgL / m.inertia_kgm2) / (2 * kPi), 1e-4);
}

// The part on the shipped rigs: the shipped inertia is m L^2, the variant's ticks at the paper's
// 2.69 Hz, and in both variants the two experiments that stay where they start are reproduced
// while exp2 (leaving antiphase) and exp3 (death) are not (docs/experiments.md).
TEST(ValidationExperiments, ShippedRigsInBothVariants) {
  const std::vector<Scenario> scenarios = testval::loadScenarios();
  ValidationLog log({});
  const ExperimentsResult r = runExperiments(2.69, scenarios, directEngines(), log, 2);
  EXPECT_NEAR(r.shipped_inertia, 0.0226 * 0.0225 * 0.0225, 1e-15);
  EXPECT_NEAR(r.variant_hz, 2.69, 2.69e-4);
  EXPECT_GT(r.inertia, 1.3 * r.shipped_inertia);
  ASSERT_EQ(r.variants.size(), 2u);
  ASSERT_EQ(r.outcomes.size(), 8u);
  for (const ExperimentOutcome& o : r.outcomes) {
    EXPECT_TRUE(o.run.report.complete) << o.scenario << " " << o.variant;
    const bool stays = o.scenario == "experiment-high-friction-antiphase" ||
                       o.scenario == "experiment-low-friction-inphase";
    EXPECT_EQ(o.reproduces(), stays) << o.scenario << " " << o.variant;
  }
}

// A part that cannot run (here: no rig to load) is said and counted as a run that stopped, not
// left out: the command then exits 3 with the rest of its report written.
TEST(ValidationExperiments, APartThatCannotRunIsCounted) {
  ValidationPlan plan;
  plan.beta_s = {};
  plan.convergence_scenarios = {};
  plan.regime_scenarios = {};
  plan.experiments = true;
  ValidationEngines engines = directEngines();
  engines.load_rig = [](const std::string& file, const std::vector<std::string>&) -> Rig {
    throw std::runtime_error("no rig " + file);
  };
  const ValidationResults r = runValidation(plan, testval::loadScenarios(), engines, {}, 1);
  ASSERT_TRUE(r.experiments.has_value());
  EXPECT_EQ(r.experiments->failure, "no rig experiment-low-friction-antiphase.yaml");
  EXPECT_EQ(r.incompleteRuns(), 1);
  EXPECT_NE(validationReportMarkdown(r, {}, {}).find("could not run: no rig"), std::string::npos);
}

}  // namespace
}  // namespace metrosync
