// Regime rules (SPEC 4) on synthetic envelopes: every rule, its order, and the boundaries.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "sim/analysis/regime.h"

namespace metrosync {
namespace {

constexpr double kPi = 3.141592653589793;
constexpr double kEps = 0.073;
constexpr double kTauEnd = 100.0;

// Rows on the shared grid up to kTauEnd; A(i, tau) and psi(j, tau), j counted from 0 (= psi_2).
std::vector<EnvelopeRow> envelope(int n, std::function<double(int, double)> A,
                                  std::function<double(int, double)> psi) {
  std::vector<EnvelopeRow> rows;
  for (long k = 0; envelopeTau(kEps, k) <= kTauEnd; ++k) {
    EnvelopeRow r;
    r.tau = envelopeTau(kEps, k);
    for (int i = 0; i < n; ++i) r.A.push_back(A(i, r.tau));
    for (int j = 0; j + 1 < n; ++j) r.psi.push_back(psi(j, r.tau));
    rows.push_back(r);
  }
  return rows;
}

// two metronomes at amplitude 1.9 (theta_c 0.9) with a given psi(tau)
Regime pair(std::function<double(double)> psi, double A2 = 1.9) {
  auto rows = envelope(
      2, [&](int i, double) { return i == 0 ? 1.9 : A2; }, [&](int, double t) { return psi(t); });
  return classifyRegime(rows, kTauEnd, kEps, {0.9, 0.9}).regime;
}

Regime constantPsi(double value) {
  return pair([=](double) { return value; });
}

// where the window starts: tau >= 0.9 tau_end
constexpr double kWindow = 0.9 * kTauEnd;

TEST(WrapToPi, LandsInMinusPiExcludedToPiIncluded) {
  EXPECT_DOUBLE_EQ(wrapToPi(kPi), kPi);
  EXPECT_DOUBLE_EQ(wrapToPi(-kPi), kPi);
  EXPECT_NEAR(wrapToPi(3 * kPi), kPi, 1e-12);
  EXPECT_NEAR(wrapToPi(2 * kPi - 0.1), -0.1, 1e-12);
  EXPECT_NEAR(wrapToPi(-0.1), -0.1, 1e-15);
  EXPECT_NEAR(wrapToPi(20 * kPi + 0.3), 0.3, 1e-12);
  EXPECT_NEAR(wrapToPi(-20 * kPi - 0.3), -0.3, 1e-12);
}

TEST(Regime, NamesAreTheSpecs) {
  EXPECT_STREQ(toString(Regime::Death), "death");
  EXPECT_STREQ(toString(Regime::Suppression), "suppression");
  EXPECT_STREQ(toString(Regime::Drift), "drift");
  EXPECT_STREQ(toString(Regime::InPhase), "in-phase");
  EXPECT_STREQ(toString(Regime::Antiphase), "antiphase");
  EXPECT_STREQ(toString(Regime::PhaseLocked), "phase-locked");
  EXPECT_STREQ(toString(Regime::Unsettled), "unsettled");
}

TEST(Regime, DeathWhenEveryMetronomeEndsBelowItsThreshold) {
  // amplitudes decaying from 1.9 to 0.5, each below its own theta_c at the end
  auto rows = envelope(
      2, [](int, double t) { return 1.9 - 1.4 * t / kTauEnd; }, [](int, double) { return 0.0; });
  EXPECT_EQ(classifyRegime(rows, kTauEnd, kEps, {0.9, 0.6}).regime, Regime::Death);
  // the same run with a lower threshold for metronome 2: it is alive, 1 is dead
  EXPECT_EQ(classifyRegime(rows, kTauEnd, kEps, {0.9, 0.4}).regime, Regime::Suppression);
}

TEST(Regime, DeadMeansStrictlyBelowThetaC) {
  EXPECT_EQ(pair([](double) { return 0.0; }, 0.9), Regime::InPhase);  // A_2 == theta_c
  EXPECT_EQ(pair([](double) { return 0.0; }, 0.8999), Regime::Suppression);
}

TEST(Regime, DeathAndSuppressionComeBeforeThePhaseRules) {
  // psi drifting fast, yet metronome 2 is dead: suppression, not drift
  EXPECT_EQ(pair([](double t) { return 0.5 * t; }, 0.3), Regime::Suppression);
  auto rows = envelope(
      2, [](int, double) { return 0.2; }, [](int, double t) { return 0.5 * t; });
  EXPECT_EQ(classifyRegime(rows, kTauEnd, kEps, {0.9, 0.9}).regime, Regime::Death);
}

TEST(Regime, DriftWhenPsiMovesMoreThanPiInTheWindow) {
  // slope s moves psi by s * 10 over the window [90, 100]
  EXPECT_EQ(pair([](double t) { return 0.4 * t; }), Regime::Drift);                   // > 3.6 > pi
  EXPECT_EQ(pair([](double t) { return -0.4 * t; }), Regime::Drift);                  // either way
  EXPECT_EQ(pair([](double t) { return 0.30 * (t - kWindow); }), Regime::Unsettled);  // 3.0 < pi
}

TEST(Regime, APhaseSlipAnywhereInTheWindowIsDrift) {
  // psi slips by 2 pi in the middle of the window and ends where it started (mod 2 pi)
  auto slip = [](double t) { return t < 95 ? 3.0 : 3.0 + 2 * kPi; };
  EXPECT_EQ(pair(slip), Regime::Drift);
}

TEST(Regime, OnlyTheLastTenPercentCounts) {
  // psi drifts by many turns up to tau = 89 and then sits at pi + 0.1 (+ many turns)
  auto settle = [](double t) { return std::min(t, 89.0) * 0.7 + 0.0; };
  const double final_value = 89.0 * 0.7;
  const double to_pi = kPi + 0.1 - std::fmod(final_value, 2 * kPi);
  EXPECT_EQ(pair([&](double t) { return settle(t) + to_pi; }), Regime::Antiphase);
  // the same psi still moving at tau = 92 is drift
  EXPECT_EQ(pair([](double t) { return std::min(t, 99.0) * 0.7; }), Regime::Drift);
}

TEST(Regime, InPhaseNearZeroOnEveryBranch) {
  EXPECT_EQ(constantPsi(0.0), Regime::InPhase);
  EXPECT_EQ(constantPsi(0.19), Regime::InPhase);
  EXPECT_EQ(constantPsi(-0.19), Regime::InPhase);
  // wrap-around near 2 pi
  EXPECT_EQ(constantPsi(2 * kPi - 0.19), Regime::InPhase);
  // unwrapped by several turns, either sign
  EXPECT_EQ(constantPsi(6 * kPi + 0.15), Regime::InPhase);
  EXPECT_EQ(constantPsi(-8 * kPi - 0.15), Regime::InPhase);
  // just outside 0.2 rad: settled elsewhere
  EXPECT_EQ(constantPsi(0.21), Regime::PhaseLocked);
  EXPECT_EQ(constantPsi(2 * kPi - 0.21), Regime::PhaseLocked);
}

TEST(Regime, AntiphaseWithinHalfARadianOfPi) {
  EXPECT_EQ(constantPsi(kPi), Regime::Antiphase);
  EXPECT_EQ(constantPsi(kPi + 0.49), Regime::Antiphase);
  EXPECT_EQ(constantPsi(kPi - 0.49), Regime::Antiphase);
  EXPECT_EQ(constantPsi(-kPi + 0.3), Regime::Antiphase);
  EXPECT_EQ(constantPsi(11 * kPi - 0.4), Regime::Antiphase);
  EXPECT_EQ(constantPsi(kPi + 0.51), Regime::PhaseLocked);
  EXPECT_EQ(constantPsi(kPi - 0.51), Regime::PhaseLocked);
  EXPECT_EQ(constantPsi(kPi / 2), Regime::PhaseLocked);
}

TEST(Regime, SettledMeansVariesByLessThanATenthOfARadian) {
  // a slow oscillation of psi around pi, peak to peak 0.09 (settled) or 0.13 (not,
  // even as sampled on the grid)
  auto wobble = [](double p2p) {
    return [=](double t) { return kPi + 0.5 * p2p * std::sin(2 * kPi * t / 3.0); };
  };
  EXPECT_EQ(pair(wobble(0.09)), Regime::Antiphase);
  EXPECT_EQ(pair(wobble(0.13)), Regime::Unsettled);
  // a slow creep of at most 0.095 over the window near 0 is in-phase, 0.108 or more is not
  EXPECT_EQ(pair([](double t) { return 0.0095 * (t - kWindow); }), Regime::InPhase);
  EXPECT_EQ(pair([](double t) { return 0.012 * (t - kWindow); }), Regime::Unsettled);
}

TEST(Regime, EveryPhaseDifferenceMustAgreeWithThreeMetronomes) {
  auto three = [](double p2, double p3) {
    auto rows = envelope(
        3, [](int, double) { return 1.5; }, [=](int j, double) { return j == 0 ? p2 : p3; });
    return classifyRegime(rows, kTauEnd, kEps, {0.9, 0.9, 0.9}).regime;
  };
  EXPECT_EQ(three(0.1, 2 * kPi - 0.1), Regime::InPhase);
  EXPECT_EQ(three(kPi, kPi + 0.2), Regime::Antiphase);
  EXPECT_EQ(three(0.0, kPi), Regime::PhaseLocked);  // 2 with 1, 3 against both
  // drift of psi_3 alone
  auto rows = envelope(
      3, [](int, double) { return 1.5; }, [](int j, double t) { return j == 0 ? 0.0 : 0.4 * t; });
  const RegimeVerdict v = classifyRegime(rows, kTauEnd, kEps, {0.9, 0.9, 0.9});
  EXPECT_EQ(v.regime, Regime::Drift);
  ASSERT_EQ(v.psi_range.size(), 2u);
  EXPECT_NEAR(v.psi_range[0], 0.0, 1e-12);
  EXPECT_GT(v.psi_range[1], kPi);
}

TEST(Regime, OneMetronomeIsAliveOrDead) {
  auto one = [](double A) {
    auto rows = envelope(
        1, [=](int, double) { return A; }, [](int, double) { return 0.0; });
    return classifyRegime(rows, kTauEnd, kEps, {0.9}).regime;
  };
  EXPECT_EQ(one(1.9), Regime::Alive);
  EXPECT_EQ(one(0.5), Regime::Death);
  EXPECT_STREQ(toString(Regime::Alive), "alive");
}

TEST(Regime, LockedMetronomesAreLeftOut) {
  // metronome 2 locked (A = 0, psi meaningless and wild), metronome 1 ticking
  auto rows = envelope(
      2, [](int i, double) { return i == 0 ? 1.9 : 0.0; }, [](int, double t) { return t; });
  EXPECT_EQ(classifyRegime(rows, kTauEnd, kEps, {0.9, 0.9}, {false, true}).regime, Regime::Alive);
  EXPECT_EQ(classifyRegime(rows, kTauEnd, kEps, {0.9, 0.9}, {true, true}).regime, Regime::None);
  EXPECT_EQ(classifyRegime(rows, kTauEnd, kEps, {0.9, 0.9}).regime, Regime::Suppression);
  // three metronomes, 3 locked: judged on psi_2 alone
  auto rows3 = envelope(
      3, [](int i, double) { return i == 2 ? 0.0 : 1.9; },
      [](int j, double t) { return j == 0 ? kPi : t; });
  const RegimeVerdict v =
      classifyRegime(rows3, kTauEnd, kEps, {0.9, 0.9, 0.9}, {false, false, true});
  EXPECT_EQ(v.regime, Regime::Antiphase);
  EXPECT_EQ(v.alive, (std::vector<int>{1, 1, -1}));
}

TEST(Regime, ShortRunIsJudgedOnItsLastRow) {
  // rows stop at tau = 50 of a run meant to reach 100: nothing in the window
  auto rows = envelope(
      2, [](int, double) { return 1.9; }, [](int, double t) { return kPi + 0.01 * t; });
  std::vector<EnvelopeRow> early;
  for (const auto& r : rows)
    if (r.tau < 50) early.push_back(r);
  const RegimeVerdict v = classifyRegime(early, kTauEnd, kEps, {0.9, 0.9});
  EXPECT_EQ(v.window_rows, 0);
  EXPECT_EQ(v.regime, Regime::Antiphase);
  EXPECT_EQ(classifyRegime(std::vector<EnvelopeRow>{}, kTauEnd, kEps, {0.9, 0.9}).regime,
            Regime::Unknown);
}

TEST(Regime, NonFiniteStateIsUnknown) {
  auto rows = envelope(
      2, [](int i, double t) { return t > 99 && i == 1 ? NAN : 1.9; },
      [](int, double) { return kPi; });
  EXPECT_EQ(classifyRegime(rows, kTauEnd, kEps, {0.9, 0.9}).regime, Regime::Unknown);
}

TEST(Regime, WindowCountsOnlyItsRowsAndReportsTheFinalPhase) {
  auto rows = envelope(
      2, [](int, double) { return 1.9; }, [](int, double) { return 4 * kPi + 3.0; });
  const RegimeVerdict v = classifyRegime(rows, kTauEnd, kEps, {0.9, 0.9});
  long expected = 0;
  for (const auto& r : rows) expected += r.tau >= kWindow;
  EXPECT_EQ(v.window_rows, expected);
  EXPECT_GT(expected, 10);
  ASSERT_EQ(v.psi_final.size(), 1u);
  EXPECT_NEAR(v.psi_final[0], 3.0, 1e-12);
  EXPECT_THROW(classifyRegime(rows, kTauEnd, kEps, {0.9}), std::invalid_argument);
}

TEST(Regime, WindowReachesBackTenPercentButNeverFewerThanFivePeriods) {
  // tau_end = 100: 10% is 10 in tau; with epsilon = 0.5 five fast periods are 5 * 2 pi * 0.5 =
  // 15.7, so the window starts at 84.3, not 90; with epsilon = 0.073 (2.3) it starts at 90
  const double eps_long = 0.5;
  const double start = kTauEnd - 5 * 2 * kPi * eps_long;
  // antiphase but for a bump of 0.5 rad between tau = 85 and 88: inside the long window only
  auto psi = [](double t) { return t > 85 && t < 88 ? kPi + 0.5 : kPi; };
  auto rowsAt = [&](double eps) {
    std::vector<EnvelopeRow> rows;
    for (long k = 0; envelopeTau(eps, k) <= kTauEnd; ++k) {
      EnvelopeRow r;
      r.tau = envelopeTau(eps, k);
      r.A = {1.9, 1.9};
      r.psi = {psi(r.tau)};
      rows.push_back(r);
    }
    return rows;
  };
  const RegimeVerdict long_window = classifyRegime(rowsAt(eps_long), kTauEnd, eps_long, {0.9, 0.9});
  EXPECT_DOUBLE_EQ(long_window.window_tau_start, start);
  EXPECT_EQ(long_window.regime, Regime::Unsettled);
  EXPECT_NE(long_window.reason.find("still move"), std::string::npos) << long_window.reason;
  long in_window = 0;
  for (const auto& r : rowsAt(eps_long)) in_window += r.tau >= start;
  EXPECT_EQ(long_window.window_rows, in_window);
  EXPECT_GE(in_window, 5);
  const RegimeVerdict short_window = classifyRegime(rowsAt(kEps), kTauEnd, kEps, {0.9, 0.9});
  EXPECT_DOUBLE_EQ(short_window.window_tau_start, kWindow);
  EXPECT_EQ(short_window.regime, Regime::Antiphase);
  EXPECT_TRUE(short_window.reason.empty());
}

TEST(Regime, ARunShorterThanFivePeriodsIsUnsettledWithItsReason) {
  // settled antiphase rows throughout: only the length of the run can make it unsettled
  const double eps = 0.1, period = 2 * kPi * eps;
  auto judge = [&](double tau_end) {
    std::vector<EnvelopeRow> rows;
    rows.push_back({0.0, {1.9, 1.9}, {kPi}});  // the start's row
    for (long k = 0; envelopeTau(eps, k) <= tau_end; ++k)
      rows.push_back({envelopeTau(eps, k), {1.9, 1.9}, {kPi}});
    rows.push_back({tau_end, {1.9, 1.9}, {kPi}});  // the final row
    return classifyRegime(rows, tau_end, eps, {0.9, 0.9});
  };
  const RegimeVerdict short_run = judge(4.9 * period);
  EXPECT_EQ(short_run.regime, Regime::Unsettled);
  EXPECT_EQ(regimeName(short_run), "unsettled");
  EXPECT_NE(short_run.reason.find("shorter than 5 fast periods"), std::string::npos)
      << short_run.reason;
  EXPECT_EQ(short_run.window_tau_start, 0.0);
  const RegimeVerdict five = judge(5.0 * period * (1 + 1e-12));
  EXPECT_EQ(five.regime, Regime::Antiphase);
  EXPECT_TRUE(five.reason.empty());
  // dead metronomes in a short run are still `unsettled`: too short to judge anything
  std::vector<EnvelopeRow> dead = {{0.0, {0.1, 0.1}, {kPi}}, {0.3, {0.1, 0.1}, {kPi}}};
  EXPECT_EQ(classifyRegime(dead, 0.3, eps, {0.9, 0.9}).regime, Regime::Unsettled);
}

}  // namespace
}  // namespace metrosync
