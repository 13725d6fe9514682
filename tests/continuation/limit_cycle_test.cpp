// Limit cycles by shooting, on a textbook system with closed forms: the Hopf normal form
//   x' = b x - y + s x r^2,  y' = x + b y + s y r^2   (r' = r (b + s r^2), theta' = 1)
// has, where b s < 0, the cycle r^2 = -b / s of period 2 pi with the nontrivial Floquet
// multiplier exp(-2 b T) (the radial eigenvalue -2 b at r^2 = -b / s, over one period); a third,
// decoupled coordinate z' = -3 z keeps the field 3-dimensional (multiplier exp(-3 T), far from the
// radial one for |b| <= 0.5).
#include "sim/analysis/continuation/limit_cycle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "base/constants.h"

namespace metrosync::continuation {
namespace {

CycleField normalForm(double sigma) {
  CycleField f;
  f.n = 3;
  f.rhs = [sigma](const Vec& u, double b) {
    const double x = u(0), y = u(1), r2 = x * x + y * y;
    Vec d(3);
    d << b * x - y + sigma * x * r2, x + b * y + sigma * y * r2, -3 * u(2);
    return d;
  };
  return f;
}

void checkBranch(double sigma, const ContinuationSettings& s) {
  const CycleBranch c = continueCycleFromHopf(normalForm(sigma), Vec::Zero(3), 0.0, s);
  EXPECT_NEAR(c.hopf_frequency, 1.0, 1e-8);
  ASSERT_GT(c.points.size(), 10u) << c.end;
  bool far = false;
  for (const CyclePoint& q : c.points) {
    const double r = std::hypot(q.y0(0), q.y0(1));
    EXPECT_NEAR(r * r, -q.p / sigma, 1e-8) << "b = " << q.p;
    EXPECT_NEAR(q.period, kTwoPi, 1e-8) << "b = " << q.p;
    EXPECT_NEAR(q.y0(2), 0.0, 1e-9);
    EXPECT_LT(q.trivial_error, 1e-6);
    // the radial multiplier: the one of the other two that is not exp(-T)
    double radial = 0;
    for (const auto& m : q.multipliers) {
      if (std::abs(m - 1.0) > 1e-4 && std::abs(m) > 1e-6) radial = m.real();
    }
    if (std::abs(q.p) > 0.05) {  // away from b = 0, where the radial one is near 1 too
      // central differences of the fixed-step flow map: ~1e-6 relative for the contracting
      // cycles, up to ~3e-5 for the most expanding ones (multiplier e^{2 pi} at b = -0.5)
      const double expected = std::exp(-2 * q.p * q.period);
      EXPECT_NEAR(radial, expected, 1e-4 * std::max(1.0, expected)) << "b = " << q.p;
    }
    EXPECT_EQ(q.stable, sigma < 0);
    far = far || std::abs(q.p) > 0.3;
  }
  EXPECT_TRUE(far) << "the branch did not reach |b| = 0.3: " << c.end;
}

TEST(LimitCycle, SupercriticalNormalFormCycleRadiusPeriodAndMultipliers) {
  ContinuationSettings s;
  s.p_min = -0.5, s.p_max = 0.5, s.step = 0.01, s.step_max = 0.05;
  checkBranch(-1.0, s);  // stable cycles for b > 0
}

TEST(LimitCycle, SubcriticalNormalFormCycleIsUnstable) {
  ContinuationSettings s;
  s.p_min = -0.5, s.p_max = 0.5, s.step = 0.01, s.step_max = 0.05;
  checkBranch(1.0, s);  // unstable cycles for b < 0
}

TEST(LimitCycle, NoComplexPairIsRefused) {
  CycleField f;
  f.n = 2;
  f.rhs = [](const Vec& u, double b) { return Vec(-u * (1 + b)); };
  ContinuationSettings s;
  s.p_min = -1, s.p_max = 1;
  EXPECT_THROW(continueCycleFromHopf(f, Vec::Zero(2), 0.0, s), std::runtime_error);
}

}  // namespace
}  // namespace metrosync::continuation
