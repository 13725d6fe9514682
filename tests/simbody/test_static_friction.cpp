// Static friction above kinetic ({law: coulomb, mu, mu_static}) in the full model, both engines,
// against closed forms. The paper's section-3A set-up (metronomes locked, the board on a spring k)
// is a mass M on a spring with dry friction: started at rest at x0, it stays put while k |x0| <
// mu_static-bar M g; beyond, it slips, oscillating about x_k = mu-bar M g / k (the kinetic bound)
// for half a period T/2 = pi sqrt(M / k), and stops at 2 x_k - x0, where it sticks if the spring's
// pull there is below the static bound.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "contact/law_registry.h"
#include "tests/common/full_model_trial.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

using testing_support::runOn;
using testing_support::Trial;

constexpr double kPi = 3.141592653589793;
constexpr double kMu = 4.6e-3, kMuStatic = 9.2e-3;  // the high-friction rollers; static twice

Rig springRig(const std::string& friction, double x0_over_static_x) {
  Rig rig = loadRigFile(std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/hard/creep.yaml",
                        {"platform.friction=" + friction, "simulation.duration=1"});
  const double k = rig.platform.spring_N_m;
  rig.platform.start_x_m = x0_over_static_x * kMuStatic * rig.totalMass() * rig.gravity_m_s2 / k;
  return rig;
}

const std::string kStiction = "{law: coulomb, mu: 4.6e-3, mu_static: 9.2e-3}";

// Below the static bound, above the kinetic one: held, on both engines; Coulomb's law with the
// kinetic mu alone lets the same push through.
TEST(StaticFriction, HoldsEveryPushBelowTheStaticBound) {
  for (const std::string engine : {"direct", "simbody"}) {
    SCOPED_TRACE(engine);
    const Rig rig = springRig(kStiction, 0.99);  // k x0 = 1.98 mu-bar M g
    const Trial held = runOn(engine, rig);
    ASSERT_TRUE(held.report.complete) << held.report.failure;
    EXPECT_EQ(held.report.counts.stick_slip, 0);
    EXPECT_EQ(held.report.final_trajectory_row.back(), 0.0) << "stuck";
    EXPECT_NEAR(held.report.final_trajectory_row[1], rig.platform.start_x_m, 1e-15);
    Rig kinetic = rig;
    kinetic.platform.friction = FrictionLaw::coulomb(kMu);
    const Trial slips = runOn(engine, kinetic);
    ASSERT_TRUE(slips.report.complete) << slips.report.failure;
    EXPECT_GE(slips.report.counts.stick_slip, 1) << "the kinetic bound alone cannot hold it";
  }
}

// Just past the static bound: one slip under the kinetic force, of half a period, ending at
// 2 x_k - x0 (the kinetic bound decides where), held there by static friction for good.
TEST(StaticFriction, SlipsAtTheStaticBoundUnderTheKineticForce) {
  for (const std::string engine : {"direct", "simbody"}) {
    SCOPED_TRACE(engine);
    const Rig rig = springRig(kStiction, 1.01);
    const double M = rig.totalMass(), k = rig.platform.spring_N_m, g = rig.gravity_m_s2;
    const double x0 = rig.platform.start_x_m, x_k = kMu * M * g / k;
    const Trial r = runOn(engine, rig);
    ASSERT_TRUE(r.report.complete) << r.report.failure;
    EXPECT_EQ(r.report.counts.stick_slip, 1) << "one stop (the start's break-free is no switch)";
    int stops = 0;
    for (const auto& [kind, row] : r.sink.events) {
      if (kind != "stick") continue;
      ++stops;
      // the direct engine locates the stop to its accuracy (1e-8 of ~0.05 s) on its dense output;
      // Simbody's event localization is looser (measured 2.4e-6 s late): 1e-5 of T/2
      const double t_tol = engine == "direct" ? 1e-6 : 1e-5 * kPi * std::sqrt(M / k);
      EXPECT_NEAR(row[0], kPi * std::sqrt(M / k), t_tol) << "half a spring period";
    }
    EXPECT_EQ(stops, 1);
    // the slip covers 2 (x0 - x_k) ~ 1e-3 m; its end to 1e-6 of that (the engines' accuracy)
    EXPECT_NEAR(r.report.final_trajectory_row[1], 2 * x_k - x0, 1e-6 * (x0 - x_k));
    EXPECT_EQ(r.report.final_trajectory_row.back(), 0.0) << "stuck at the end";
    // the energy ledger (spring energy against friction's work) closes
    if (engine == "direct") {
      ASSERT_TRUE(r.report.has_ledger);
    }
    if (r.report.has_ledger) {
      EXPECT_LE(std::abs(r.report.ledger.relativeResidual()), 1e-6);
    }
  }
}

}  // namespace
}  // namespace metrosync
