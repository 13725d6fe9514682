// Stribeck friction ({law: stribeck, mu, mu_static, stribeck_velocity, exponent};
// contact/stribeck.cpp) in the full model, both engines. The paper's section-3A set-up
// (metronomes locked, the board on a spring k: yaml/rigs/hard/creep.yaml) is a mass M on a spring
// with dry friction:
//   stick  started at rest at x0 it stays put while k |x0| < mu_static-bar M g (closed form);
//   slip   beyond, M xddot = -k x - sign(xdot) M g (mu + (mu_static - mu) exp(-(|xdot| / V)^E))
//          until xdot returns to 0, where it sticks (|k x| below the static bound). No closed form:
//          the reference is that ODE integrated by classical RK4 with the stop bisected, converged
//          (h and h/2 agree to 1e-12 of the slip). Either Coulomb limit (the static bound
//          throughout, or the kinetic one) slips for exactly half a spring period pi sqrt(M / k),
//          to 2 x_s - x0 or 2 x_k - x0; the Stribeck slip, sped up once its force falls, then
//          slowed by its rise near the stop, lasts a third longer and ends between the two, 1.5%
//          of their gap past the kinetic one (1e4 times the engines' tolerance): a law that
//          ignored the speed would miss both.
// And at mu_static == mu the law is Coulomb's, bit for bit on both engines (the same arithmetic:
// mu + 0 * e == mu exactly, so the slip force -(mu N) mode is the same double).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "contact/law_registry.h"
#include "models/scaling.h"
#include "tests/common/full_model_trial.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

using testing_support::expectSameBits;
using testing_support::runOn;
using testing_support::Trial;

constexpr double kPi = 3.141592653589793;
constexpr double kMu = 4.6e-3, kMuStatic = 9.2e-3;  // the high-friction rollers; static twice
constexpr double kV = 5e-4;                         // m/s: the slip's peak speed is 4.6 mm/s

Rig springRig(const FrictionLaw& law, double x0_over_static_x) {
  Rig rig = loadRigFile(std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/hard/creep.yaml",
                        {"simulation.duration=1"});
  rig.platform.friction = law;
  const double k = rig.platform.spring_N_m;
  rig.platform.start_x_m = x0_over_static_x * kMuStatic * rig.totalMass() * rig.gravity_m_s2 / k;
  return rig;
}

FrictionLaw stribeck(double mu, double mu_static, double V, double E = 2.0) {
  return FrictionLaw(stribeckLaw(), {mu, mu_static, V, E});
}

// The reference slip from rest at x0 > 0 (moving left): its stop time and position.
struct Stop {
  double t, x;
};

Stop referenceStop(const Rig& rig, double h) {
  const double M = rig.totalMass(), k = rig.platform.spring_N_m, N = M * rig.gravity_m_s2;
  const std::vector<double>& p = rig.platform.friction.values();
  // M a = -k x + N (mu + d e): friction pushes right while the board slips left
  const auto accel = [&](double x, double v) {
    return (-k * x + N * (p[0] + (p[1] - p[0]) * std::exp(-std::pow(std::abs(v) / p[2], p[3])))) /
           M;
  };
  const auto step = [&](double& x, double& v, double dt) {
    const double k1x = v, k1v = accel(x, v);
    const double k2x = v + 0.5 * dt * k1v, k2v = accel(x + 0.5 * dt * k1x, v + 0.5 * dt * k1v);
    const double k3x = v + 0.5 * dt * k2v, k3v = accel(x + 0.5 * dt * k2x, v + 0.5 * dt * k2v);
    const double k4x = v + dt * k3v, k4v = accel(x + dt * k3x, v + dt * k3v);
    x += dt / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  };
  double t = 0, x = rig.platform.start_x_m, v = 0;
  for (;;) {
    double xn = x, vn = v;
    step(xn, vn, h);
    if (t > 0 && vn >= 0) break;  // the slip ends within [t, t + h]
    t += h, x = xn, v = vn;
  }
  double lo = 0, hi = h;  // RK4 over a partial step is continuous in its length: bisect it
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    double xm = x, vm = v;
    step(xm, vm, mid);
    (vm < 0 ? lo : hi) = mid;
  }
  step(x, v, lo);
  return {t + lo, x};
}

TEST(Stribeck, TheReferenceIsConvergedAndBetweenTheCoulombLimits) {
  const Rig rig = springRig(stribeck(kMu, kMuStatic, kV), 1.01);
  const double M = rig.totalMass(), k = rig.platform.spring_N_m, g = rig.gravity_m_s2;
  const double x0 = rig.platform.start_x_m, x_k = kMu * M * g / k, x_s = kMuStatic * M * g / k;
  const Stop a = referenceStop(rig, 2e-5), b = referenceStop(rig, 1e-5);
  const double slip = x0 - b.x;
  EXPECT_NEAR(a.x, b.x, 1e-12 * slip) << "RK4 converged";
  EXPECT_NEAR(a.t, b.t, 1e-9) << "RK4 converged";
  // strictly between the limits, and a third longer than their half period
  const double gap = (2 * x_s - x0) - (2 * x_k - x0);
  EXPECT_GT(b.x - (2 * x_k - x0), 0.01 * gap);
  EXPECT_GT((2 * x_s - x0) - b.x, 0.5 * gap);
  EXPECT_GT(b.t, 1.3 * kPi * std::sqrt(M / k));
  EXPECT_LT(std::abs(k * b.x), kMuStatic * M * g) << "held where it stops";
}

// Below the static bound: held, on both engines (the kinetic mu alone would let it through).
TEST(Stribeck, HoldsEveryPushBelowTheStaticBound) {
  for (const std::string engine : {"direct", "simbody"}) {
    SCOPED_TRACE(engine);
    const Rig rig = springRig(stribeck(kMu, kMuStatic, kV), 0.99);  // k x0 = 1.98 mu-bar M g
    const Trial held = runOn(engine, rig);
    ASSERT_TRUE(held.report.complete) << held.report.failure;
    EXPECT_EQ(held.report.counts.stick_slip, 0);
    EXPECT_EQ(held.report.final_trajectory_row.back(), 0.0) << "stuck";
    EXPECT_NEAR(held.report.final_trajectory_row[1], rig.platform.start_x_m, 1e-15);
    const Trial slips = runOn(engine, springRig(stribeck(kMu, kMu, kV), 0.99));
    ASSERT_TRUE(slips.report.complete) << slips.report.failure;
    EXPECT_GE(slips.report.counts.stick_slip, 1) << "the kinetic bound alone cannot hold it";
  }
}

// Just past the static bound: one slip, ending where the reference ends, held there for good.
TEST(Stribeck, SlipsAsTheConvergedReferenceOnBothEngines) {
  for (const std::string engine : {"direct", "simbody"}) {
    SCOPED_TRACE(engine);
    Rig rig = springRig(stribeck(kMu, kMuStatic, kV), 1.01);
    rig.sim.accuracy = 1e-10;
    const Stop ref = referenceStop(rig, 1e-5);
    const double slip = rig.platform.start_x_m - ref.x;
    const Trial r = runOn(engine, rig);
    ASSERT_TRUE(r.report.complete) << r.report.failure;
    EXPECT_EQ(r.report.counts.stick_slip, 1) << "one stop (the start's break-free is no switch)";
    int stops = 0;
    for (const auto& [kind, row] : r.sink.events) {
      if (kind != "stick") continue;
      ++stops;
      // at accuracy 1e-10: Simbody's event localization is the looser (measured 7.6e-8 s late
      // at 1e-10, 1.2e-9 s at 1e-12, 4.5e-6 s at the rig's default accuracy)
      EXPECT_NEAR(row[0], ref.t, 1e-6) << "the stop's time";
    }
    EXPECT_EQ(stops, 1);
    EXPECT_NEAR(r.report.final_trajectory_row[1], ref.x, 1e-6 * slip);
    EXPECT_EQ(r.report.final_trajectory_row.back(), 0.0) << "stuck at the end";
    if (engine == "direct") {
      ASSERT_TRUE(r.report.has_ledger);
    }
    if (r.report.has_ledger) {
      EXPECT_LE(std::abs(r.report.ledger.relativeResidual()), 1e-6);
    }
  }
}

// The velocity scales like a velocity (V / (x_scale omega0)), the exponent not at all, and a
// scaled rig's values come back from physical units.
TEST(Stribeck, ScalesItsVelocityLikeTheBoardsVelocity) {
  const Rig rig = springRig(stribeck(kMu, kMuStatic, kV, 1.5), 1.01);
  const ScaledParams sp = computeScaled(rig);
  const double omega0 = 1.0 / sp.time_scale_s;
  EXPECT_DOUBLE_EQ(*sp.friction.value("stribeck_velocity"), kV / (sp.x_scale_m * omega0));
  EXPECT_EQ(*sp.friction.value("exponent"), 1.5);
  EXPECT_DOUBLE_EQ(*sp.friction.value("mu_static") / *sp.friction.value("mu"), 2.0);
  // the start's velocity in the same units: a board started at V is at the scaled V
  Rig moving = rig;
  moving.platform.start_v_m_s = kV;
  EXPECT_DOUBLE_EQ(computeScaled(moving).xdot0, *sp.friction.value("stribeck_velocity"));
}

// mu_static == mu: Coulomb's law bit for bit, on a board with ticking metronomes (stick-slip with
// ticks) and on the spring rig (a slip from rest); a positive gap changes the run.
TEST(Stribeck, EqualCoefficientsRunAsCoulombsLawBitForBit) {
  const std::string file =
      std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/bench/experiment-short.yaml";
  for (const std::string engine : {"direct", "simbody"}) {
    SCOPED_TRACE(engine);
    Rig board = loadRigFile(file, {"simulation.duration=4"});
    const double mu = *board.platform.friction.value("mu");
    const Trial coulomb = runOn(engine, board);
    board.platform.friction = stribeck(mu, mu, 2e-3);
    expectSameBits(coulomb, runOn(engine, board));
    EXPECT_GT(coulomb.report.counts.stick_slip, 0) << "the case must exercise stick and slip";
    board.platform.friction = stribeck(mu, 2 * mu, 2e-3);
    EXPECT_NE(runOn(engine, board).sink.trajectory, coulomb.sink.trajectory);
    const Trial spring = runOn(engine, springRig(FrictionLaw::coulomb(kMuStatic), 1.01));
    expectSameBits(spring, runOn(engine, springRig(stribeck(kMuStatic, kMuStatic, kV), 1.01)));
  }
}

}  // namespace
}  // namespace metrosync
