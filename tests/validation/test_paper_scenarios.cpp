// The paper's eight simulations (section 4), from the shipped rigs, with the slow flow: the
// regimes and the details the paper's text and captions describe. The statements are typed in
// here from the paper (psi = phi_1 - phi_2; alpha > 0 makes metronome 2 the faster one).
#include <gtest/gtest.h>

#include <cmath>

#include "base/constants.h"
#include "fixtures.h"

namespace metrosync {
namespace {

struct PaperRun {
  Scenario scenario;
  ModelRun slow;
};

// the shipped rig as shipped: its epsilon (0.073) and tau (300)
PaperRun runPaper(const std::string& name) {
  PaperRun r{testval::loadScenario(name), {}};
  r.slow = runSlowModel(r.scenario.scaled, r.scenario.scaled.epsilon, r.scenario.scaled.tau_end);
  EXPECT_TRUE(r.slow.report.complete) << name << ": " << r.slow.report.failure;
  return r;
}

double offPi(const ModelRun& m) {
  return std::abs(wrapToPi(m.final().psi[0] - kPi));
}

// A locked phase of the slow flow varies by 1e-12..1e-5 over the window (the most where it
// settles algebraically onto the edge of the stuck family, f4.2: beta ~ (s - 1)^2 as s -> 1+).
// 1e-3 separates "stationary" from a drift or a residual oscillation.
constexpr double kStationary = 1e-3;

TEST(PaperScenarios, F41LowFrictionNearAntiphaseStartEndsInPhase) {
  const PaperRun r = runPaper("f4.1");
  EXPECT_EQ(r.slow.verdict.regime, Regime::InPhase);
  // it left pi: psi went up to 2 pi (the paper's bottom panel), not back down to 0
  EXPECT_NEAR(r.slow.final().psi[0], 2 * kPi, 0.2);
}

TEST(PaperScenarios, F42LocksNearAntiphaseButNotAtPi) {
  const PaperRun r = runPaper("f4.2");
  EXPECT_EQ(r.slow.verdict.regime, Regime::Antiphase);
  // "the phase difference never converges to pi": more than 0.05 away (5e7 times the slow
  // flow's accuracy), and stationary, not still creeping towards pi
  EXPECT_GT(offPi(r.slow), 0.05) << "psi = " << r.slow.final().psi[0];
  EXPECT_LT(r.slow.verdict.psi_range[0], kStationary);
  // "the amplitude of both metronomes ultimately increases and reaches a fixed value": from 1.9
  EXPECT_GT(r.slow.final().A[0], 1.9);
  EXPECT_NEAR(r.slow.final().A[0], r.slow.final().A[1], 1e-6);
}

TEST(PaperScenarios, F43FrictionTakesInPhaseToSuppressionToDeath) {
  const PaperRun low = runPaper("f4.3-mu0.2"), mid = runPaper("f4.3-mu0.3"),
                 high = runPaper("f4.3-mu0.4");
  EXPECT_EQ(low.slow.verdict.regime, Regime::InPhase);
  EXPECT_EQ(mid.slow.verdict.regime, Regime::Suppression);
  // "the dead metronome follows along ... with a phase difference close to pi" (the SPEC's
  // antiphase band, 0.5 rad)
  EXPECT_LT(offPi(mid.slow), 0.5);
  EXPECT_EQ(high.slow.verdict.regime, Regime::Death);
}

TEST(PaperScenarios, F44DetuningLocksThenSuppressesTheFasterThenKills) {
  const PaperRun a = runPaper("f4.4-alpha0.2"), b = runPaper("f4.4-alpha2"),
                 c = runPaper("f4.4-alpha4");
  const double tc = 0.9;
  // alpha = 0.2: phase-locked near antiphase, the faster metronome (2) at the lower amplitude
  // (by more than 0.01: far above the slow flow's accuracy, far below the figure's visible gap)
  EXPECT_EQ(a.slow.verdict.regime, Regime::Antiphase);
  EXPECT_LT(a.slow.verdict.psi_range[0], kStationary);
  EXPECT_GT(a.slow.final().A[0] - a.slow.final().A[1], 0.01);
  // alpha = 2: still locked near pi, the faster metronome (2) suppressed below theta_c
  EXPECT_EQ(b.slow.verdict.regime, Regime::Suppression);
  EXPECT_LT(b.slow.final().A[1], tc);
  EXPECT_GT(b.slow.final().A[0], tc);
  EXPECT_LT(offPi(b.slow), 0.5);
  EXPECT_LT(b.slow.verdict.psi_range[0], kStationary);
  // alpha = 4: metronome 1 suppresses 2 "for a long time" (here: 50 in tau, over 15 times the
  // amplitudes' relaxation time 2 / nu ~ 3), then both die
  EXPECT_EQ(c.slow.verdict.regime, Regime::Death);
  double suppressed = 0;
  const auto& env = c.slow.envelope;
  for (size_t k = 1; k < env.size(); ++k)
    if (env[k].A[0] >= tc && env[k].A[1] < tc) suppressed += env[k].tau - env[k - 1].tau;
  EXPECT_GT(suppressed, 50.0);
}

// The library's checks (what `validate` reports) agree with the statements above, and fail when
// held against the wrong outcome.
TEST(PaperScenarios, LibraryChecksPassOnTheirOwnScenarioAndFailOnOthers) {
  for (const auto& spec : shippedScenarios()) {
    if (spec.outcome == PaperOutcome::None) continue;
    SCOPED_TRACE(spec.name);
    const PaperRun r = runPaper(spec.name);
    for (const Check& c : paperChecks(spec.outcome, r.slow, r.scenario.scaled))
      EXPECT_TRUE(c.pass) << c.what << ": " << c.detail;
  }
  const PaperRun in_phase = runPaper("f4.3-mu0.2");
  for (PaperOutcome wrong : {PaperOutcome::Death, PaperOutcome::NearAntiphaseOffPi,
                             PaperOutcome::FasterSuppressed, PaperOutcome::SuppressionThenDeath}) {
    const auto checks = paperChecks(wrong, in_phase.slow, in_phase.scenario.scaled);
    bool any_failed = false;
    for (const Check& c : checks) any_failed = any_failed || !c.pass;
    EXPECT_TRUE(any_failed) << "an in-phase run passed the checks of outcome "
                            << static_cast<int>(wrong);
  }
}

}  // namespace
}  // namespace metrosync
