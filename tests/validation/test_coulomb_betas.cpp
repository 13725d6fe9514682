// beta1, beta2 (eq. d2, contact/averaged_response.h) against the full model's own Coulomb element:
// the Simbody element driven by B sin t to its periodic steady state, its acceleration projected
// on sin t and cos t over one period (contact/simbody/driven_coulomb.h). Two independent codes:
// the closed forms solve for the stick and slip instants analytically; the element finds them by
// integrating the motion and locating its witness.
#include <gtest/gtest.h>

#include <cmath>

#include "base/constants.h"
#include "contact/averaged_response.h"
#include "contact/simbody/driven_coulomb.h"

namespace metrosync {
namespace {

// The bound. The harness gets the switch instants to ~1e-12 (integrator at 1e-10,
// witness localized far tighter) and integrates the piecewise-smooth y'' exactly, so it measures
// the betas to ~1e-11: 1e-7 leaves four orders of margin, and would still catch an error in the
// closed forms' stick time t1 of ~1e-7 or a wrong regime boundary.
constexpr double kTol = 1e-7;

void expectBetasMatch(double s) {
  SCOPED_TRACE("s = " + std::to_string(s));
  const DrivenCoulombMeasurement m = measureDrivenCoulomb(s);
  ASSERT_TRUE(m.periodic) << "no periodic steady state after " << m.periods << " periods";
  EXPECT_NEAR(m.beta1, coulombBeta1(s), kTol);
  EXPECT_NEAR(m.beta2, coulombBeta2(s), kTol);
  // the element's switch pattern per period is the closed form's regime: stuck (no switch),
  // stick-slip (slip, stick, slip back, stick: 4), pure slip (two reversals)
  const size_t expected = s <= 1 ? 0 : (s <= kCoulombSlipThreshold ? 4 : 2);
  EXPECT_EQ(m.switches.size(), expected);
}

TEST(CoulombBetas, ElementMatchesClosedFormsAcrossTheRange) {
  // log-spaced over [0.5, 10] (the range), avoiding the boundaries (tested below)
  for (double s : {0.5, 0.8, 1.05, 1.3, 1.6, 2.2, 3.5, 6.0, 10.0}) expectBetasMatch(s);
}

TEST(CoulombBetas, ElementMatchesClosedFormsAtTheStickThreshold) {
  // s = 1 +- 1e-6: just stuck, and a slip of ~4e-3 per half period (u^2 ~ 18 (s - 1))
  expectBetasMatch(1.0 - 1e-6);
  expectBetasMatch(1.0 + 1e-6);
}

TEST(CoulombBetas, ElementMatchesClosedFormsAtTheSlipThreshold) {
  // s_b = sqrt(1 + pi^2/4) +- 1e-6: a stick of vanishing length, or none
  EXPECT_NEAR(kCoulombSlipThreshold, std::sqrt(1 + kPi * kPi / 4), 1e-15);
  expectBetasMatch(kCoulombSlipThreshold - 1e-6);
  expectBetasMatch(kCoulombSlipThreshold + 1e-6);
}

// The measurement is sharp: the element's betas at s and at s (1 + 1e-4) differ by far more than
// the tolerance, so agreement is not the two codes sharing a smooth, slow function by chance.
TEST(CoulombBetas, MeasurementResolvesSmallChangesOfTheDrive) {
  const DrivenCoulombMeasurement a = measureDrivenCoulomb(1.4), b = measureDrivenCoulomb(1.4001);
  ASSERT_TRUE(a.periodic && b.periodic);
  EXPECT_GT(std::abs(b.beta1 - a.beta1), 100 * kTol);
  EXPECT_GT(std::abs(b.beta2 - a.beta2), 100 * kTol);
  EXPECT_NEAR(b.beta1 - a.beta1, coulombBeta1(1.4001) - coulombBeta1(1.4), 2 * kTol);
}

}  // namespace
}  // namespace metrosync
