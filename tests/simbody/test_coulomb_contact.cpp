// The Coulomb contact on its own: a unit mass on a slider with unit Coulomb friction, driven by a
// prescribed force B sin t (the paper's eq. c1). Its steady response must be the closed-form
// periodic solution y_p of appendix "ac" (contact/averaged_response.h, independent code).
#include <Simbody.h>
#include <gtest/gtest.h>

#include <cmath>

#include "contact/averaged_response.h"
#include "contact/simbody/driven_coulomb_harness.h"

namespace metrosync {
namespace {

using namespace SimTK;

using Harness = DrivenCoulombHarness;

// Runs from rest at t = 0 for `periods` drive periods, then samples the last period.
void checkAgainstClosedForm(double B, int periods, double tol) {
  Harness h(B);
  State s = h.system.getDefaultState();
  h.settleAtRest(s);
  RungeKuttaMersonIntegrator integ(h.system);
  integ.setAccuracy(1e-12);
  // a stuck platform changes nothing the error control sees: cap the step so that the stick
  // margin (which crosses zero twice per half period) cannot cross twice inside one step
  integ.setMaximumStepSize(0.1);
  TimeStepper ts(h.system, integ);
  ts.initialize(s);
  const double t_start = 2 * Pi * (periods - 1);
  ts.stepTo(t_start);
  const double y_ref = h.slider.getOneQ(ts.getState(), MobilizerQIndex(0));
  const double yp_ref = coulombYp(t_start, B);
  double worst_v = 0, worst_y = 0;
  for (int k = 1; k <= 200; ++k) {
    const double t = t_start + 2 * Pi * k / 200.0;
    ts.stepTo(t);
    const State& st = ts.getState();
    const double v = h.slider.getOneU(st, MobilizerUIndex(0));
    const double y = h.slider.getOneQ(st, MobilizerQIndex(0)) - y_ref;
    worst_v = std::max(worst_v, std::abs(v - coulombYpDot(t, B)));
    worst_y = std::max(worst_y, std::abs(y - (coulombYp(t, B) - yp_ref)));
  }
  EXPECT_LT(worst_v, tol) << "B = " << B;
  EXPECT_LT(worst_y, tol) << "B = " << B;
  EXPECT_GT(h.switches().size(), 2u * (periods - 1)) << "B = " << B << ": too few switches";
}

TEST(DrivenCoulombContact, HoldingForceIsMinusTheAppliedForce) {
  // a constant push P on a stuck platform: friction must supply -P
  for (double P : {0.3, -0.7}) {
    Harness h(0.0);
    Force::MobilityConstantForce(h.forces, h.slider, 0, P);
    h.system.realizeTopology();
    State s = h.system.getDefaultState();
    EXPECT_EQ(h.settleAtRest(s), PlatformMode::Stuck);
    EXPECT_NEAR(h.contact->holdingForce(s), -P, 1e-12);
    EXPECT_NEAR(h.slider.getOneUDot(s, MobilizerUIndex(0)), 0.0, 1e-12);
  }
  // beyond the bound it slips the way it is pushed
  Harness h(0.0);
  Force::MobilityConstantForce(h.forces, h.slider, 0, -1.5);
  h.system.realizeTopology();
  State s = h.system.getDefaultState();
  EXPECT_EQ(h.settleAtRest(s), PlatformMode::SlipNegative);
  EXPECT_NEAR(h.slider.getOneUDot(s, MobilizerUIndex(0)), -0.5, 1e-12);
}

// Tolerance 1e-8 (the bound): the integrator runs at 1e-12 and the switches are located
// within a window of ~1e-13 in time, so the sampled velocity is good to ~1e-10.
TEST(DrivenCoulombContact, StickSlipResponseMatchesClosedFormAtB14) {
  checkAgainstClosedForm(1.4, 12, 1e-8);
}

TEST(DrivenCoulombContact, PureSlipResponseMatchesClosedFormAtB2) {
  checkAgainstClosedForm(2.0, 40, 1e-8);
}

TEST(DrivenCoulombContact, StaysStillForWeakDrive) {
  for (double B : {0.5, 0.999, 1.0}) {
    Harness h(B);
    State s = h.system.getDefaultState();
    h.settleAtRest(s);
    RungeKuttaMersonIntegrator integ(h.system);
    integ.setAccuracy(1e-10);
    TimeStepper ts(h.system, integ);
    ts.initialize(s);
    ts.stepTo(6 * Pi);
    EXPECT_EQ(h.contact->mode(ts.getState()), PlatformMode::Stuck) << "B = " << B;
    EXPECT_EQ(h.slider.getOneQ(ts.getState(), MobilizerQIndex(0)), 0.0) << "B = " << B;
    EXPECT_TRUE(h.switches().empty()) << "B = " << B;
  }
}

}  // namespace
}  // namespace metrosync
