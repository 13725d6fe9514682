// The full model against independent truth: closed forms of the paper (section 3A's linear decay,
// eq. A_star, J_c), conservation laws (momentum with a free platform, the energy ledger),
// symmetries (exact antiphase keeps the platform stuck; identical metronomes in phase are one
// metronome of twice the size; the order of the metronomes in the rig does not matter).
#include <gtest/gtest.h>

#include <cmath>

#include "base/constants.h"
#include "rigs.h"
#include "sim/engines/simbody/simbody_engine.h"

namespace metrosync {
namespace {

// Section 3A: platform on a spring, metronomes locked. Between two reversals the platform is a
// harmonic oscillator about +-mu-bar M g / kappa, so its amplitude drops by 4 mu-bar M g / kappa
// per period T = 2 pi sqrt(M / kappa): slope = 4 mu-bar M g / (T kappa) = mu-bar T g / pi^2.
TEST(FullModel, SpringPlatformDecaysLinearlyAtTheCoulombRate) {
  Rig rig = testrigs::experiment(4.6e-3, 6.0);
  for (auto& m : rig.metronomes) m.locked = true;
  rig.platform.spring_N_m = 30.0;
  rig.platform.start_x_m = -0.05;
  rig.sim.accuracy = 1e-10;
  MemorySink sink;
  RunReport r = runSimbody(networkOfOne(rig), sink);
  ASSERT_TRUE(r.complete) << r.failure;
  // the reversals: the platform stops at each extreme and slips back ("slip" events)
  std::vector<double> t, amp;
  for (const auto& [kind, row] : sink.events)
    if (std::string(kind) == "slip") {
      t.push_back(row[0]);
      amp.push_back(std::abs(row[1]));
    }
  ASSERT_GE(t.size(), 8u) << "too few reversals";
  const double M = rig.totalMass(), g = rig.gravity_m_s2, kappa = rig.platform.spring_N_m;
  const double T = 2 * kPi * std::sqrt(M / kappa);
  const double slope_theory = rig.platform.friction.valueOr("mu", 0.0) * T * g / (kPi * kPi);
  EXPECT_NEAR(slope_theory, 4 * rig.platform.friction.valueOr("mu", 0.0) * M * g / (T * kappa),
              1e-15);
  // least-squares slope of |x| at the reversals against time
  double st = 0, sa = 0, stt = 0, sta = 0;
  const double n = static_cast<double>(t.size());
  for (size_t k = 0; k < t.size(); ++k) {
    st += t[k];
    sa += amp[k];
    stt += t[k] * t[k];
    sta += t[k] * amp[k];
  }
  const double slope = -(n * sta - st * sa) / (n * stt - st * st);
  // 1e-6 relative (the bound): reversals are located to ~1e-12 s at accuracy 1e-10
  EXPECT_NEAR(slope / slope_theory, 1.0, 1e-6);
  // and every half period is the same: reversals T/2 apart
  for (size_t k = 1; k < t.size(); ++k) EXPECT_NEAR(t[k] - t[k - 1], T / 2, 1e-7 * T);
  EXPECT_EQ(r.counts.escapements[0], 0);
}

// One metronome on a fixed platform settles to A_star (eq. A_star); the difference is the
// asymptotics' O(epsilon), so it must shrink with epsilon.
TEST(FullModel, SingleMetronomeSettlesToAStarWithErrorShrinkingWithEpsilon) {
  const double nu = 0.7, J = 2.8, tc = 0.9;
  const double a_star =
      J / (kPi * nu) * std::sqrt(2 * (1 + std::sqrt(1 - kPi * kPi * nu * nu * tc * tc / (J * J))));
  std::vector<double> errors;
  for (double eps : {0.04, 0.01}) {
    ScaledRigInput in = testrigs::scaledPair(eps, FrictionLaw::fixed(), 30.0, 0.0);
    in.metronomes.resize(1);
    Rig rig = rigFromScaled(in);
    EXPECT_TRUE(rig.platform.friction == FrictionLaw::fixed());
    MemorySink sink;
    RunReport r = runSimbody(networkOfOne(rig), sink);
    ASSERT_TRUE(r.complete) << r.failure;
    errors.push_back(std::abs(r.final_row.A[0] - a_star));
    EXPECT_GT(r.counts.escapements[0], 100);
  }
  // O(epsilon): a quarter of epsilon gives well under half the error
  EXPECT_LT(errors[0], 0.1) << "eps = 0.04";
  EXPECT_LT(errors[1], 0.5 * errors[0]);
}

TEST(FullModel, MetronomeBelowCriticalImpulseStops) {
  ScaledRigInput in = testrigs::scaledPair(0.02, FrictionLaw::fixed(), 30.0, 0.0, 2.5);
  in.metronomes.resize(1);
  in.metronomes[0].J = 0.9 * kPi * in.metronomes[0].nu * in.metronomes[0].theta_c;  // J < J_c
  MemorySink sink;
  RunReport r = runSimbody(networkOfOne(rigFromScaled(in)), sink);
  ASSERT_TRUE(r.complete) << r.failure;
  EXPECT_LT(r.final_row.A[0], in.metronomes[0].theta_c);
  // after the last tick the amplitude only decays
  EXPECT_LT(sink.envelope.back().A[0], sink.envelope[sink.envelope.size() / 2].A[0]);
}

// Identical metronomes in exact antiphase: the forces on the platform cancel at every instant
// and the ticks come in cancelling pairs, so a Coulomb platform never moves.
TEST(FullModel, ExactAntiphaseKeepsCoulombPlatformStill) {
  ScaledRigInput in = testrigs::scaledPair(0.073, FrictionLaw::coulomb(0.2), 20.0, 0.0);
  in.metronomes[0].theta0 = 0.0;
  in.metronomes[0].thetadot0 = -1.9;
  in.metronomes[1].theta0 = 0.0;
  in.metronomes[1].thetadot0 = 1.9;
  MemorySink sink;
  RunReport r = runSimbody(networkOfOne(rigFromScaled(in)), sink);
  ASSERT_TRUE(r.complete) << r.failure;
  EXPECT_EQ(r.counts.stick_slip, 0);
  EXPECT_GT(r.counts.escapements[0], 50);
  EXPECT_EQ(r.counts.escapements[0], r.counts.escapements[1]);
  for (const auto& row : sink.trajectory) {
    ASSERT_EQ(row[1], 0.0) << "t = " << row[0];
    ASSERT_EQ(row[2], 0.0) << "t = " << row[0];
    ASSERT_EQ(row.back(), 0.0) << "t = " << row[0];
  }
  // the pendulums stay mirror images
  const auto& last = sink.trajectory.back();
  EXPECT_NEAR(last[3], -last[5], 1e-9);
}

// A free platform (law: none): the horizontal momentum p = M xdot + sum m_i L_i cos(theta_i)
// thetadot_i is conserved by every step and every tick (the escapement is internal).
TEST(FullModel, FreePlatformConservesHorizontalMomentum) {
  Rig rig = testrigs::experiment(0.0, 10.0);
  rig.platform.friction = FrictionLaw::none();
  rig.platform.start_v_m_s = 0.01;
  rig.sim.accuracy = 1e-10;
  MemorySink sink;
  RunReport r = runSimbody(networkOfOne(rig), sink);
  ASSERT_TRUE(r.complete) << r.failure;
  ASSERT_GT(r.counts.escapements[0], 20);
  const double M = rig.totalMass();
  auto momentum = [&](const std::vector<double>& row) {
    double p = M * row[2];
    for (size_t i = 0; i < rig.metronomes.size(); ++i) {
      const auto& m = rig.metronomes[i];
      p += m.pendulum_mass_kg * m.length_m * std::cos(row[3 + 2 * i]) * row[4 + 2 * i];
    }
    return p;
  };
  const double p0 = momentum(sink.trajectory.front());
  double scale = std::abs(p0);
  for (const auto& row : sink.trajectory)
    scale = std::max(
        scale, rig.metronomes[0].pendulum_mass_kg * rig.metronomes[0].length_m * std::abs(row[4]));
  double worst = 0;
  for (const auto& row : sink.trajectory) worst = std::max(worst, std::abs(momentum(row) - p0));
  for (const auto& ev : sink.events) worst = std::max(worst, std::abs(momentum(ev.second) - p0));
  // integration error only: accuracy 1e-10 over ~200 periods
  EXPECT_LT(worst / scale, 1e-7);
}

// Every effect at once: Coulomb stick-slip, pivot damping, escapement, a platform spring,
// detuned metronomes and a locked one. The ledger must close.
TEST(FullModel, EnergyLedgerClosesWithEveryEffectOn) {
  Rig rig = testrigs::experiment(2.0e-3, 30.0);
  rig.metronomes[1].length_m *= 1.05;
  rig.metronomes[1].inertia_kgm2 *= 1.05 * 1.05;
  MetronomeSpec locked = rig.metronomes[0];
  locked.locked = true;
  rig.metronomes.push_back(locked);
  rig.platform.spring_N_m = 2.0;
  rig.sim.accuracy = 1e-9;
  MemorySink sink;
  RunReport r = runSimbody(networkOfOne(rig), sink);
  ASSERT_TRUE(r.complete) << r.failure;
  ASSERT_TRUE(r.has_ledger);
  // the spring keeps the platform going: mostly slip reversals, counted apart from stick <-> slip
  EXPECT_GT(r.counts.stick_slip + r.counts.slip_reversals, 100);
  EXPECT_GT(r.counts.escapements[0], 100);
  EXPECT_GT(r.ledger.friction_out_J, 0);
  EXPECT_GT(r.ledger.damping_out_J, 0);
  EXPECT_LT(std::abs(r.ledger.relativeResidual()), 1e-6)
      << "residual " << r.ledger.residual_J() << " J";
}

// Identical metronomes started exactly in phase tick at the same instant; the pair is exactly one
// metronome with twice the mass, inertia, damping and impulse (e1.1a-c), whichever order the
// two simultaneous ticks are registered in.
TEST(FullModel, SimultaneousTicksEqualOneDoubledMetronome) {
  Rig pair = testrigs::experiment(1.0e-3, 8.0);
  pair.sim.accuracy = 1e-10;
  for (auto& m : pair.metronomes) {
    m.start_angle_rad = 0.6;
    m.start_rate_rad_s = 0.0;
  }
  Rig one = pair;
  one.metronomes.resize(1);
  auto& m = one.metronomes[0];
  m.box_mass_kg *= 2;
  m.pendulum_mass_kg *= 2;
  m.inertia_kgm2 *= 2;
  m.damping_kg_s *= 2;
  m.impulse_Nms *= 2;
  MemorySink s2, s1;
  RunReport r2 = runSimbody(networkOfOne(pair), s2);
  RunReport r1 = runSimbody(networkOfOne(one), s1);
  ASSERT_TRUE(r2.complete && r1.complete);
  EXPECT_EQ(r2.counts.escapements[0], r2.counts.escapements[1]);
  EXPECT_EQ(r2.counts.escapements[0], r1.counts.escapements[0]);
  EXPECT_EQ(r2.counts.stick_slip, r1.counts.stick_slip);
  ASSERT_EQ(s2.trajectory.size(), s1.trajectory.size());
  double worst = 0;
  for (size_t k = 0; k < s1.trajectory.size(); ++k) {
    worst = std::max(worst, std::abs(s2.trajectory[k][3] - s1.trajectory[k][3]));
    worst = std::max(worst, std::abs(s2.trajectory[k][5] - s1.trajectory[k][3]));
    worst = std::max(worst, 1e3 * std::abs(s2.trajectory[k][1] - s1.trajectory[k][1]));
  }
  // two integrations of the same equations at accuracy 1e-10 (x weighted: it is ~1e-3 rad-sized)
  EXPECT_LT(worst, 1e-7);
}

// Listing the metronomes in the other order gives the same motion.
TEST(FullModel, ResultDoesNotDependOnMetronomeOrder) {
  Rig a = testrigs::experiment(1.5e-3, 8.0);
  a.metronomes[1].length_m *= 1.02;
  a.metronomes[1].inertia_kgm2 *= 1.02 * 1.02;
  Rig b = a;
  std::swap(b.metronomes[0], b.metronomes[1]);
  MemorySink sa, sb;
  RunReport ra = runSimbody(networkOfOne(a), sa), rb = runSimbody(networkOfOne(b), sb);
  ASSERT_TRUE(ra.complete && rb.complete);
  EXPECT_EQ(ra.counts.escapements[0], rb.counts.escapements[1]);
  EXPECT_EQ(ra.counts.stick_slip, rb.counts.stick_slip);
  const auto& la = sa.trajectory.back();
  const auto& lb = sb.trajectory.back();
  EXPECT_NEAR(la[3], lb[5], 1e-6);
  EXPECT_NEAR(la[5], lb[3], 1e-6);
  EXPECT_NEAR(la[1], lb[1], 1e-8);
}

// Grazing: a pendulum whose swing tops out a hair above theta_c must tick (two crossings of
// theta_c within far less than one step); a hair below, it must not.
TEST(FullModel, GrazingCrossingIsNotMissed) {
  for (double rel : {1e-7, -1e-7}) {
    ScaledRigInput in = testrigs::scaledPair(0.02, FrictionLaw::fixed(), 0.03, 0.0);
    in.metronomes.resize(1);
    in.metronomes[0].nu = 0.0;
    Rig rig = rigFromScaled(in);
    auto& m = rig.metronomes[0];
    // start at the bottom with the energy that reaches theta_max (the exact pendulum)
    const double theta_max = m.theta_c_rad * (1 + rel);
    const double w0 = std::sqrt(2 * m.pendulum_mass_kg * rig.gravity_m_s2 * m.length_m *
                                (1 - std::cos(theta_max)) / m.inertia_kgm2);
    m.start_angle_rad = 0;
    m.start_rate_rad_s = w0;
    rig.sim.t_end_s = 0.5 * 2 * kPi /
                      std::sqrt(m.pendulum_mass_kg * rig.gravity_m_s2 * m.length_m /
                                m.inertia_kgm2);  // half a swing
    MemorySink sink;
    RunReport r = runSimbody(networkOfOne(rig), sink);
    ASSERT_TRUE(r.complete) << r.failure;
    EXPECT_EQ(r.counts.escapements[0], rel > 0 ? 1 : 0) << "theta_max/theta_c - 1 = " << rel;
  }
}

}  // namespace
}  // namespace metrosync
