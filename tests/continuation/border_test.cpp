// Border crossings: the f4.4 state at alpha = 3.9 continued in theta_c of metronome 2. Its
// suppressed amplitude A_2 ~ 0.22 lies below theta_c = 0.9; lowering theta_c through A_2 switches
// the escapement on (a jump of the phase equation, models/slow_flow.h), which the continuation
// must find exactly where |z_2| = theta_c,2 and nowhere else.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/continuation/fixtures.h"

namespace metrosync::continuation {
namespace {

using testing::f44;

ScaledParams withThetaC2(double tc) {
  static const ScaledParams base = f44(3.9);
  ScaledParams p = base;
  p.theta_c[1] = tc;
  return p;
}

TEST(Border, EscapementSwitchFoundWhereAEqualsThetaC) {
  SlowFlowProblem prob(withThetaC2, 0.9, 0);
  const SettledState st = settleFromStart(prob.params(0.9), 300);
  ASSERT_TRUE(st.settled) << st.why;
  const auto x = solveLocked(prob, prob.pack(st.z, prob.omegaGuess(0.9, st.z)), 0.9);
  ASSERT_TRUE(x.has_value());
  ContinuationSettings s;
  s.p_min = 0.05, s.p_max = 0.9, s.step = 0.02, s.step_max = 0.05;
  const auto branches = continueFrom(prob.system(), *x, 0.9, s);
  int found = 0, left = 0;
  for (const Branch& b : branches)
    for (const Bifurcation& e : b.special) {
      if (e.type != BifurcationType::Border) continue;
      const Vec xb = e.point.y.head(prob.system().n);
      const auto A = prob.amplitudes(xb);
      if (e.border == 1 && e.detail.find("boundary equilibrium") != std::string::npos) {
        ++found;
        EXPECT_NEAR(A[1], e.point.p(), 1e-10);  // on the border: |z_2| = theta_c,2
        EXPECT_EQ(e.point.region[1], 0);        // reached from the disengaged side
        EXPECT_NE(e.detail.find("A_2 = theta_c"), std::string::npos) << e.detail;
      } else if (e.border == 1) {
        ++left;
        EXPECT_NEAR(A[1], e.point.p(), 1e-10);    // it leaves the border on it
        EXPECT_EQ(e.point.region[1], kOnBorder);  // from the border states
      }
    }
  EXPECT_EQ(found, 1);
  EXPECT_EQ(left, 1);
  // through the border: on to the end of the range, with ticking states past it
  bool ticking = false, at_end = false;
  for (const Branch& b : branches)
    for (const BranchPoint& q : b.points) {
      ticking = ticking || q.region[1] == 1;
      at_end = at_end || q.p() == s.p_min;
    }
  EXPECT_TRUE(ticking);
  EXPECT_TRUE(at_end);
  // every point lies in the region whose formulas it solves (or on its border)
  for (const Branch& b : branches)
    for (const BranchPoint& q : b.points) {
      const Vec bd = prob.system().borders(q.y.head(prob.system().n), q.p());
      for (int k = 0; k < bd.size(); ++k)
        EXPECT_TRUE(std::abs(bd(k)) < 1e-9 || (bd(k) > 0) == (q.region[k] == 1))
            << "border " << k << " at theta_c,2 = " << q.p();
    }
}

}  // namespace
}  // namespace metrosync::continuation
