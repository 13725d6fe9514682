// Regime rules (SPEC 4) on synthetic envelopes: every rule, its order, and the boundaries.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "base/constants.h"
#include "contact/law_registry.h"
#include "sim/analysis/regime.h"

namespace metrosync {
namespace {

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
  // (A = 0.64 at the window's start tau = 90: a threshold of 0.65 is above it throughout)
  EXPECT_EQ(classifyRegime(rows, kTauEnd, kEps, {0.9, 0.65}).regime, Regime::Death);
  // the same run with a lower threshold for metronome 2: it is alive, 1 is dead
  EXPECT_EQ(classifyRegime(rows, kTauEnd, kEps, {0.9, 0.4}).regime, Regime::Suppression);
}

TEST(Regime, DeadMeansBelowThetaCThroughoutTheWindowNotAtTheEndAlone) {
  // metronome 2 decays linearly from 1.9 at the window's start (tau = 90) to 0.5 at the end: it
  // ends below theta_c = 0.9 but was above it for most of the window, so it is not dead (the old
  // rule, final amplitude alone, called it dead): it is dying, and the run is unsettled; with A_2
  // below 0.9 from tau = 90 on it is dead
  auto judge = [](double from) {
    auto rows = envelope(
        2,
        [=](int i, double t) {
          return i == 0 ? 1.9 : (t < kWindow ? from : from - (from - 0.5) * (t - kWindow) / 10);
        },
        [](int, double) { return 0.0; });
    return classifyRegime(rows, kTauEnd, kEps, {0.9, 0.9});
  };
  EXPECT_EQ(judge(1.9).regime, Regime::Unsettled);
  EXPECT_NE(judge(1.9).reason.find("metronome 2 falls below theta_c"), std::string::npos);
  EXPECT_EQ(judge(1.9).alive, (std::vector<int>{1, 1}));
  EXPECT_EQ(judge(0.89).regime, Regime::Suppression);
  EXPECT_EQ(judge(0.89).alive, (std::vector<int>{1, 0}));
}

TEST(Regime, AnAmplitudeSwingingThroughThetaCIsAliveNotDying) {
  // metronome 2 exchanges energy with 1: A_2 = 1.8 + 1.6 cos(2 pi (t - c) / 3) swings through
  // theta_c = 0.9 every 3 in tau, several times in the window (tau 90 to 100), and ends below it
  // at 1.8 + 1.6 cos(1.2 pi) = 0.51 (c puts the last row at 0.6 of a swing), past its lowest
  // point (the earlier minima, sampled every fast period of 0.46, are below 0.4): alive, not dying
  const double t_last = envelope(1, [](int, double) { return 1.0; }, {}).back().tau;
  const double c = t_last - 0.6 * 3;
  auto rows = envelope(
      2, [c](int i, double t) { return i == 0 ? 1.9 : 1.8 + 1.6 * std::cos(kTwoPi * (t - c) / 3); },
      [](int, double) { return 0.0; });
  const RegimeVerdict v = classifyRegime(rows, kTauEnd, kEps, {0.9, 0.9});
  ASSERT_LT(rows.back().A[1], 0.9);  // it ends below theta_c
  EXPECT_EQ(v.alive, (std::vector<int>{1, 1}));
  EXPECT_EQ(v.reason.find("dying"), std::string::npos) << v.reason << " " << toString(v.regime);
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

TEST(Regime, APhaseSlipInTheWindowsLastHalfIsDrift) {
  // psi slips by 2 pi in the window's last half (its settling part, tau >= 95) and ends where it
  // started (mod 2 pi)
  auto slipAt = [](double at) { return [=](double t) { return t < at ? 3.0 : 3.0 + 2 * kPi; }; };
  EXPECT_EQ(pair(slipAt(97)), Regime::Drift);
  // the same slip in the window's first half, locked after it: the state the run ends in (issue
  // 37: main said drift, and antiphase for the same run 10% longer)
  EXPECT_EQ(pair(slipAt(92)), Regime::Antiphase);
}

// Issue 37's cell: an in-phase state that grows unstable slips into antiphase inside the window
// (psi 0.05 -> pi + 0.2 over tau 91-93, the flagship map at psi0 = 0.063, mu = 0.45), then holds:
// antiphase, as the same run twice as long says; the window's range is kept in psi_range.
TEST(Regime, ATransientThatEndsInTheWindowsFirstHalfIsNotTheState) {
  auto psi = [](double t) {
    return t < 91 ? 0.05 * std::sin(t) : t < 93 ? 0.05 + (kPi + 0.15) * (t - 91) / 2 : kPi + 0.2;
  };
  auto rows = envelope(
      2, [](int, double) { return 1.9; }, [&](int, double t) { return psi(t); });
  const RegimeVerdict v = classifyRegime(rows, kTauEnd, kEps, {0.9, 0.9});
  EXPECT_EQ(v.regime, Regime::Antiphase);
  EXPECT_GT(v.psi_range[0], kPi);
  EXPECT_LT(v.psi_settle_range[0], 1e-12);
  EXPECT_DOUBLE_EQ(v.settle_tau_start, 95.0);
  // still moving in the last half: not settled (drift over the window)
  auto late = [](double t) { return t < 96 ? 0.0 : (kPi + 0.2) * std::min(1.0, (t - 96) / 2); };
  EXPECT_EQ(pair(late), Regime::Drift);
}

TEST(Regime, TheSettlingPartIsTheWindowsLastHalfButAtLeastFivePeriods) {
  const double five = 5 * 2 * kPi * kEps;  // 2.29
  EXPECT_DOUBLE_EQ(RegimeWindow(100.0, kEps).settleTauStart(), 95.0);
  // a run of 12: the window is its last 5 periods (its 10% is 1.2 < 2.29), and so is the settling
  // part
  EXPECT_DOUBLE_EQ(RegimeWindow(12.0, kEps).tauStart(), 12.0 - five);
  EXPECT_DOUBLE_EQ(RegimeWindow(12.0, kEps).settleTauStart(), 12.0 - five);
  // a window of 8 periods: its last half would be 4 periods, so the settling part is 5
  const double tau = 8 * five / 5 / 0.1;  // the window (10%) is 8 periods
  EXPECT_NEAR(RegimeWindow(tau, kEps).settleTauStart(), tau - five, 1e-12);
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

TEST(Regime, SettledMeansVariesByLessThanATenthOfARadianOverTheWindowsLastHalf) {
  // a slow oscillation of psi around pi, peak to peak 0.09 (settled) or 0.13 (not,
  // even as sampled on the grid)
  auto wobble = [](double p2p) {
    return [=](double t) { return kPi + 0.5 * p2p * std::sin(2 * kPi * t / 3.0); };
  };
  EXPECT_EQ(pair(wobble(0.09)), Regime::Antiphase);
  EXPECT_EQ(pair(wobble(0.13)), Regime::Unsettled);
  // a slow creep near 0 of at most 0.095 over the window is in-phase, 0.108 or more is not
  EXPECT_EQ(pair([](double t) { return 0.0095 * (t - kWindow); }), Regime::InPhase);
  EXPECT_EQ(pair([](double t) { return 0.012 * (t - kWindow); }), Regime::Unsettled);
  // a creep never ends: by 0.087 over the window's last half (rows from tau = 95.2 to 99.8), 0.19
  // over the window, it is not settled though the last half alone would be (a transient that
  // ended moves its last half by at most a quarter of the window's range; hard/n100.yaml in the
  // full model, docs/regimes.md)
  EXPECT_EQ(pair([](double t) { return 0.019 * (t - kWindow); }), Regime::Unsettled);
  // an approach that slows down (time constant 3): about 0.29 rad over the window, 0.05 of it in
  // the last half (ratio 0.16): the transient has ended, in-phase
  EXPECT_EQ(pair([](double t) { return 0.3 * std::exp(-(t - kWindow) / 3.0); }), Regime::InPhase);
  // ... with time constant 6 (ratio 0.3) it has not ended: unsettled
  EXPECT_EQ(pair([](double t) { return 0.3 * std::exp(-(t - kWindow) / 6.0); }), Regime::Unsettled);
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

// Rows with the platform's mode given as a full model gives it (trajectory rows before each
// envelope row): stuck throughout, or sliding in the periods where slip(tau) is true.
RegimeVerdict withPlatform(std::vector<EnvelopeRow> rows, std::function<bool(double)> slip,
                           std::vector<double> theta_c = {0.9, 0.9}) {
  RegimeWindow w(kTauEnd, kEps);
  double x = 0.0;
  for (const auto& r : rows) {
    // a slip and a stick within the period move the platform by 0.1 (scaled)
    if (slip(r.tau)) {
      w.platformMode(1, x);
      x += 0.1;
    }
    w.platformMode(0, x);
    w.add(r);
  }
  return classifyRegime(w, theta_c);
}

TEST(Regime, UncoupledWhenThePlatformNeverSlipsInTheRun) {
  auto rows = envelope(
      2, [](int, double) { return 1.9; }, [](int, double) { return kPi; });
  // never slipped: uncoupled, though psi sits at pi
  const RegimeVerdict never = withPlatform(rows, [](double) { return false; });
  EXPECT_EQ(never.regime, Regime::Uncoupled);
  EXPECT_EQ(regimeName(never), "uncoupled");
  EXPECT_EQ(never.platform_slipped, 0);
  EXPECT_EQ(never.platform_slipped_before, 0);
  // stuck in the window after it slid before: coupling moved it and brought psi where it stuck,
  // so the phase rules judge it (issue 37: main said uncoupled, and antiphase for the run whose
  // board stuck inside the window)
  const RegimeVerdict stuck = withPlatform(rows, [](double t) { return t < kWindow - 1; });
  EXPECT_EQ(stuck.regime, Regime::Antiphase);
  EXPECT_EQ(stuck.platform_slipped, 0);
  EXPECT_EQ(stuck.platform_slipped_before, 1);
  // one slip in the last period of the window: coupled, antiphase
  const RegimeVerdict slips = withPlatform(rows, [](double t) { return t > kTauEnd - 0.5; });
  EXPECT_EQ(slips.regime, Regime::Antiphase);
  EXPECT_EQ(slips.platform_slipped, 1);
  // slips in every period that leave the platform where it was (micro-slips at ticks): still
  // uncoupled; the same slips moving it by 2e-6 over the window: antiphase
  auto microSlips = [&](double step) {
    RegimeWindow w(kTauEnd, kEps);
    double x = 0.0;
    for (const auto& r : rows) {
      w.platformMode(1, x);
      x += r.tau >= kWindow ? step : 0.0;
      w.platformMode(0, x);
      w.add(r);
    }
    return classifyRegime(w, {0.9, 0.9});
  };
  EXPECT_EQ(microSlips(0.0).regime, Regime::Uncoupled);
  EXPECT_GT(microSlips(0.0).platform_slip_rows, 10);
  const long window_rows = microSlips(0.0).window_rows;
  EXPECT_EQ(microSlips(2e-6 / (window_rows - 1)).regime, Regime::Antiphase);
  EXPECT_EQ(microSlips(0.5e-6 / (window_rows - 1)).regime, Regime::Uncoupled);
  // before the window the same: micro-slips that moved the board by 0.5e-6 over the whole run
  // leave it uncoupled, by 2e-6 coupled (the whole run's travel, from its start)
  auto slipsBefore = [&](double travel) {
    RegimeWindow w(kTauEnd, kEps);
    const double step = travel / 100;
    double x = 0.0;
    for (const auto& r : rows) {
      const bool slips = r.tau < kWindow && x < travel - step / 2;
      w.platformMode(slips ? 1 : 0, x);
      x += slips ? step : 0.0;
      w.platformMode(0, x);
      w.add(r);
    }
    return classifyRegime(w, {0.9, 0.9});
  };
  EXPECT_EQ(slipsBefore(0.5e-6).regime, Regime::Uncoupled);
  EXPECT_EQ(slipsBefore(0.5e-6).platform_slipped_before, 0);
  EXPECT_EQ(slipsBefore(2e-6).regime, Regime::Antiphase);
  EXPECT_EQ(slipsBefore(2e-6).platform_slipped_before, 1);
  // no platform information at all (validation, old callers): the phase rules as before
  EXPECT_EQ(classifyRegime(rows, kTauEnd, kEps, {0.9, 0.9}).platform_slipped, -1);
  // death and suppression win over uncoupled (amplitude rules first)
  EXPECT_EQ(withPlatform(rows, [](double) { return false; }, {2.0, 2.0}).regime, Regime::Death);
  EXPECT_EQ(withPlatform(rows, [](double) { return false; }, {0.9, 2.0}).regime,
            Regime::Suppression);
  // N = 3 with one dead: the dead count, then uncoupled
  auto rows3 = envelope(
      3, [](int i, double) { return i == 2 ? 0.1 : 1.9; }, [](int, double) { return 1.0; });
  EXPECT_EQ(regimeName(withPlatform(rows3, [](double) { return false; }, {0.9, 0.9, 0.9})),
            "suppressed:1;uncoupled");
}

TEST(Regime, TheSlowFlowsPlatformSlipsWhenTheDriveExceedsMu) {
  // two metronomes at A = 1.9 in antiphase drive nothing (|Z| = 0), in phase |Z| = 3.8
  auto judge = [](double psi, const FrictionLaw& law) {
    auto rows = envelope(
        2, [](int, double) { return 1.9; }, [=](int, double) { return psi; });
    RegimeWindow w(kTauEnd, kEps);
    w.setEnvelopePlatform(law);
    for (const auto& r : rows) w.add(r);
    return classifyRegime(w, {0.9, 0.9}).regime;
  };
  EXPECT_EQ(judge(0.0, FrictionLaw::coulomb(3.7)), Regime::InPhase);    // s = 3.8 / 3.7 > 1
  EXPECT_EQ(judge(0.0, FrictionLaw::coulomb(3.9)), Regime::Uncoupled);  // s < 1
  EXPECT_EQ(judge(kPi, FrictionLaw::coulomb(0.1)), Regime::Uncoupled);  // |Z| = 0
  EXPECT_EQ(judge(kPi, FrictionLaw::viscous(0.0)), Regime::Antiphase);  // always moves
  EXPECT_EQ(judge(0.0, FrictionLaw::fixed()), Regime::Uncoupled);       // never moves
  // the law decides whether it holds: static friction above kinetic holds a drive of 3.8 that
  // the kinetic coefficient alone would not (a set-valued law that is not Coulomb's is not
  // "always slipping")
  const FrictionLaw held(staticCoulombLaw(), {3.7, 3.9});
  EXPECT_EQ(judge(0.0, held), Regime::Uncoupled);
  EXPECT_EQ(judge(0.0, FrictionLaw(staticCoulombLaw(), {3.7, 3.7})), Regime::InPhase);
}

// Issue 37's cause: approaching antiphase, the slow flow's board sticks once the drive |Z| falls
// below mu, and psi freezes near pi. Whether that happens before the window or inside it, the
// label is the state's (main: uncoupled when before, antiphase when inside).
TEST(Regime, TheSlowFlowsBoardStuckAfterSlippingIsJudgedByItsPhase) {
  // psi from pi - 2 toward pi at 0.1 per unit of tau until |Z| = 3.8 sin((pi - psi) / 2) < mu
  auto judge = [](double stick_at, double mu, double psi0) {
    auto psi = [=](double t) {
      return kPi - std::max(kPi - psi0 - 0.1 * t, kPi - psi0 - 0.1 * stick_at);
    };
    auto rows = envelope(
        2, [](int, double) { return 1.9; }, [&](int, double t) { return psi(t); });
    RegimeWindow w(kTauEnd, kEps);
    w.setEnvelopePlatform(FrictionLaw::coulomb(mu));
    for (const auto& r : rows) w.add(r);
    return classifyRegime(w, {0.9, 0.9});
  };
  // stuck at psi = pi - 0.2 (|Z| = 0.38 < 0.5): at tau = 18, long before the window, or at 91,
  // inside it (its settling part is still)
  for (double at : {18.0, 91.0}) {
    const RegimeVerdict v = judge(at, 0.5, kPi - 2 - 0.1 * (at - 18));
    EXPECT_EQ(v.regime, Regime::Antiphase) << "stuck at " << at;
    EXPECT_EQ(v.platform_slipped, at < kWindow ? 0 : 1);
  }
  EXPECT_EQ(judge(18.0, 0.5, kPi - 2).platform_slipped_before, 1);
  // stuck far from pi (psi = pi - 1, |Z| = 1.82 < mu = 2): phase-locked there
  EXPECT_EQ(judge(10.0, 2.0, kPi - 2).regime, Regime::PhaseLocked);
  // a board the drive never moved: psi stays at its start, uncoupled
  EXPECT_EQ(judge(0.0, 0.5, kPi - 0.2).regime, Regime::Uncoupled);
}

// N = 3..8 metronomes at A = 1.5 with constant phases phi_i (relative to phi_1 = phases[0])
RegimeVerdict fixedPhases(const std::vector<double>& phases) {
  auto rows = envelope(
      static_cast<int>(phases.size()), [](int, double) { return 1.5; },
      [&](int j, double) { return phases[0] - phases[j + 1]; });
  return classifyRegime(rows, kTauEnd, kEps, std::vector<double>(phases.size(), 0.9));
}

TEST(Regime, SplayWhenThePhasesAreEvenlySpread) {
  EXPECT_EQ(regimeName(fixedPhases({0.0, 2 * kPi / 3, 4 * kPi / 3})), "splay");
  EXPECT_EQ(regimeName(fixedPhases({0.0, 2 * kPi / 3 + 0.15, 4 * kPi / 3})), "splay");
  EXPECT_EQ(regimeName(fixedPhases({0.0, 2 * kPi / 3 + 0.25, 4 * kPi / 3})), "phase-locked");
  EXPECT_EQ(regimeName(fixedPhases({0.0, kPi / 2, kPi, 3 * kPi / 2})), "splay");
  // five evenly but in the order 1 3 5 2 4: still splay (the set of phases counts)
  std::vector<double> five;
  for (int k : {0, 2, 4, 1, 3}) five.push_back(2 * kPi * k / 5);
  EXPECT_EQ(regimeName(fixedPhases(five)), "splay");
  // two in one cluster: clusters, not splay
  EXPECT_EQ(regimeName(fixedPhases({0.0, 0.05, kPi})), "clusters:2+1");
}

TEST(Regime, InPhaseNeedsEveryPairWithinTheBoundNotAChain) {
  EXPECT_EQ(regimeName(fixedPhases({0.0, 0.15, 0.3})), "phase-locked");  // 1-3 differ by 0.3
  EXPECT_EQ(regimeName(fixedPhases({0.0, 0.1, 0.2})), "in-phase");
}

TEST(Regime, ClustersCarryTheirMembersAndPhaseDifferences) {
  const RegimeVerdict v = fixedPhases({0.0, 2.0, 0.05, 2.1, -0.05});
  EXPECT_EQ(regimeName(v), "clusters:3+2");
  ASSERT_EQ(v.cluster_members.size(), 2u);
  EXPECT_EQ(v.cluster_members[0], (std::vector<int>{1, 3, 5}));
  EXPECT_EQ(v.cluster_members[1], (std::vector<int>{2, 4}));
  ASSERT_EQ(v.cluster_phase.size(), 2u);
  EXPECT_DOUBLE_EQ(v.cluster_phase[0], 0.0);
  EXPECT_NEAR(v.cluster_phase[1], 2.05, 1e-12);  // circular means 0 and 2.05
}

TEST(Regime, ClustersThatSlidePastEachOtherAreNotClusters) {
  // 1 and 2 locked in phase, 3 drifting against both by 0.4 per unit tau: drift, not clusters
  auto rows = envelope(
      3, [](int, double) { return 1.5; }, [](int j, double t) { return j == 0 ? 0.0 : 0.4 * t; });
  const RegimeVerdict v = classifyRegime(rows, kTauEnd, kEps, {0.9, 0.9, 0.9});
  EXPECT_EQ(regimeName(v), "drift");
  EXPECT_EQ(v.cluster_sizes, (std::vector<int>{2, 1}));
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
