// The fast stick-slip duration (contact/slip_duration.h: a Chebyshev start and one Newton step)
// against the converged reference iteration, and the pieces the averaged response is made of.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "base/constants.h"
#include "contact/averaged_response.h"
#include "contact/slip_duration.h"

namespace metrosync {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

std::vector<double> qGrid() {
  std::vector<double> q;
  for (int k = 0; k <= 12000; ++k) q.push_back(0.5 * kPi * k / 12000.0);  // the table's range
  for (int k = 0; k <= 8000; ++k) q.push_back(std::pow(10.0, -9.0 + 9.0 * k / 8000.0));  // 1e-9..1
  q.push_back(0.5 * kPi);
  q.push_back(std::nextafter(0.5 * kPi, 0.0));
  q.push_back(1e-20);
  q.push_back(1e-300);
  return q;
}

TEST(SlipDuration, FastAgreesWithTheReferenceToAFewUlp) {
  // The Chebyshev start is good to ~1e-12 relative; one Newton step squares that, so what remains
  // is the rounding of the step itself (a few ulp of u). A start only 1e-7 accurate would leave
  // ~1e-14 here and fail.
  double worst = 0.0;
  for (double q : qGrid()) {
    const double ref = coulombSlipDurationReference(q);
    const double fast = coulombSlipDuration(q);
    if (q == 0.0) {
      EXPECT_EQ(fast, 0.0);
      continue;
    }
    if (q == 1e-300) {  // the reference's g underflows there; the fast path returns 3 q
      EXPECT_EQ(fast, 3e-300);
      continue;
    }
    ASSERT_TRUE(std::isfinite(fast)) << "q = " << q;
    const double rel = std::fabs(fast - ref) / ref;
    worst = std::fmax(worst, rel);
    EXPECT_LE(rel, 8 * kEps) << "q = " << q;
  }
  RecordProperty("worst_relative", std::to_string(worst));
}

TEST(SlipDuration, SolvesTheSlipEquation) {
  // g(u) = q with g computed independently from std::sin / std::cos (at u >= 0.5, where the
  // direct formula loses no more than a few digits); g' >= 1/3, so |u - root| <= 3 |g(u) - q|.
  for (int k = 1; k <= 2000; ++k) {
    const double q = 0.5 * kPi * k / 2000.0;
    const double u = coulombSlipDuration(q);
    if (u < 0.5) continue;
    const double g = (u - std::sin(u)) / (1.0 - std::cos(u));
    EXPECT_NEAR(g, q, 1e-14 * (1.0 + q)) << "q = " << q;
  }
  EXPECT_NEAR(coulombSlipDuration(0.5 * kPi), kPi, 4 * kEps * kPi);  // g(pi) = pi/2
  EXPECT_EQ(coulombSlipDuration(0.0), 0.0);
  EXPECT_EQ(coulombSlipDuration(-1.0), 0.0);
  EXPECT_TRUE(std::isnan(coulombSlipDuration(std::numeric_limits<double>::infinity())));
  EXPECT_EQ(coulombSlipDuration(std::numeric_limits<double>::quiet_NaN()),
            0.0);  // as the reference
}

TEST(SlipDuration, ContinuationBeyondTheSlipThresholdIsTheReference) {
  for (double q : {1.5708, 2.0, 5.0, 100.0})
    EXPECT_EQ(coulombSlipDuration(q), coulombSlipDurationReference(q)) << "q = " << q;
}

TEST(SlipDuration, ElementaryFunctionsMatchTheirDefinitions) {
  // at u >= 0.3 the direct forms lose at most ~3 digits; below, the series are checked against
  // their leading terms
  for (double u = 0.3; u < 6.0; u += 0.01) {
    EXPECT_NEAR(uMinusSin(u), u - std::sin(u), 1e-15 * u);
    EXPECT_NEAR(oneMinusCos(u), 1.0 - std::cos(u), 1e-15);
    EXPECT_NEAR(halfSquareMinusOneMinusCos(u), 0.5 * u * u - (1.0 - std::cos(u)), 1e-14 * u * u);
  }
  for (double u : {1e-3, 1e-5, 1e-8}) {
    EXPECT_NEAR(uMinusSin(u) / (u * u * u / 6.0), 1.0 - u * u / 20.0, 1e-15);
    EXPECT_NEAR(halfSquareMinusOneMinusCos(u) / (u * u * u * u / 24.0), 1.0 - u * u / 30.0, 1e-15);
  }
}

}  // namespace
}  // namespace metrosync

namespace metrosync {
namespace {

TEST(StickSlipResponse, TablesAgreeWithTheReferenceEvaluation) {
  // coulombResponseIn(StickSlip, s) interpolates N1 / q^5, N2 / q^4 in q^2 on 1 < s <= s_b; the
  // reference evaluates the closed forms from the converged u. Measured: 1e-14 relative at worst
  // (rounding of both); a table two orders of magnitude worse would fail. Beyond s_b the
  // continuation is the reference itself.
  double worst = 0.0;
  auto check = [&](double s) {
    const AveragedResponse a = coulombResponseIn(CoulombRegime::StickSlip, s);
    const AveragedResponse b = coulombStickSlipReference(s);
    ASSERT_GT(b.beta1, 0.0) << "s = " << s;
    ASSERT_GT(b.beta2, 0.0) << "s = " << s;
    const double r =
        std::fmax(std::fabs(a.beta1 - b.beta1) / b.beta1, std::fabs(a.beta2 - b.beta2) / b.beta2);
    worst = std::fmax(worst, r);
    EXPECT_LE(r, 1e-13) << "s = " << s;
  };
  const double sb = kCoulombSlipThreshold;
  for (int k = 1; k <= 40000; ++k) check(1.0 + (sb - 1.0) * k / 40000.0);
  for (int k = 0; k <= 4000; ++k) check(1.0 + std::pow(10.0, -15.0 + 14.0 * k / 4000.0));
  check(sb);
  RecordProperty("worst_relative", std::to_string(worst));
  for (double s : {sb + 1e-9, 2.0, 2.5}) {
    const AveragedResponse a = coulombResponseIn(CoulombRegime::StickSlip, s);
    const AveragedResponse b = coulombStickSlipReference(s);
    EXPECT_EQ(a.beta1, b.beta1) << "s = " << s;
    EXPECT_EQ(a.beta2, b.beta2) << "s = " << s;
  }
  EXPECT_EQ(coulombResponseIn(CoulombRegime::StickSlip, 1.0).beta1, 0.0);
  EXPECT_EQ(coulombResponseIn(CoulombRegime::StickSlip, 0.5).beta2, 0.0);
}

}  // namespace
}  // namespace metrosync
