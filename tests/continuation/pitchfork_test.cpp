// Branch points and branch switching on the pitchfork x' = p x - x^3 (the symmetric case that
// identical metronomes make generic): from the trivial branch x = 0 the continuation must find the
// branch point at p = 0 and switch onto x^2 = p, stable, while x = 0 loses its stability there.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/analysis/continuation/arclength.h"

namespace metrosync::continuation {
namespace {

ContinuationSystem pitchfork() {
  ContinuationSystem sys;
  sys.n = 1;
  sys.residual = [](const Vec& x, double p, const Region&) {
    return Vec::Constant(1, p * x(0) - x(0) * x(0) * x(0));
  };
  sys.eigenvalues = [](const Vec& x, double p, const Region&) {
    return CVec::Constant(1, p - 3 * x(0) * x(0));
  };
  return sys;
}

TEST(Pitchfork, BranchPointFoundAndSwitched) {
  ContinuationSettings s;
  s.p_min = -0.5, s.p_max = 0.5, s.step = 0.03, s.step_max = 0.1;
  const auto branches = continueFrom(pitchfork(), Vec::Zero(1), -0.5, s);
  ASSERT_GE(branches.size(), 2u);
  int bps = 0;
  for (const Bifurcation& b : branches[0].special)
    if (b.type == BifurcationType::Branch) {
      ++bps;
      EXPECT_NEAR(b.point.p(), 0.0, 1e-9);
      EXPECT_NEAR(b.point.y(0), 0.0, 1e-9);
    }
  EXPECT_EQ(bps, 1);
  for (const BranchPoint& q : branches[0].points) {
    EXPECT_NEAR(q.y(0), 0.0, 1e-12);
    if (std::abs(q.p()) > 1e-9) {
      EXPECT_EQ(q.stable, q.p() < 0);
    }
  }
  // the new branch: x^2 = p, stable away from the branch point, reaching p = 0.5 both ways
  const Branch& b = branches[1];
  double xmin = 0, xmax = 0;
  for (const BranchPoint& q : b.points) {
    // 1e-10: its first point is the branch point, located to ~1e-11 in arclength
    EXPECT_NEAR(q.y(0) * q.y(0), q.p(), 1e-10);
    if (std::abs(q.y(0)) > 1e-6) {
      EXPECT_TRUE(q.stable);
    }
    xmin = std::min(xmin, q.y(0)), xmax = std::max(xmax, q.y(0));
  }
  EXPECT_NEAR(xmax, std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(xmin, -std::sqrt(0.5), 1e-9);
}

}  // namespace
}  // namespace metrosync::continuation
