// One metronome on a Coulomb platform, continued in mu: a closed-form branch. Its ticking states
// solve the amplitude equation (e3.1a with N = 1, w_1 = A^2 real)
//   G(A, s) = A (beta2(s) + nu / 2) - (J / pi) sqrt(1 - theta_c^2 / A^2) = 0,   mu = A / s,
// so along the curve G = 0 in the (s, A) plane mu = A / s; its smallest value is the fold where
// the ticking state dies as mu decreases. Found here independently: for each s both roots A of
// G(., s) by bisection, the minimum of A / s over s by golden section.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "contact/averaged_response.h"
#include "tests/continuation/fixtures.h"

namespace metrosync::continuation {
namespace {

using testing::singleMetronome;
using testing::singleTicking;
using testing::worstResidual;

constexpr double kNu = 0.7, kJ = 2.8, kThetaC = 0.9;

double amplitudeRate(double A, double s) {
  return testing::amplitudeRate(A, s, kNu);
}

struct FollowResult {
  std::vector<Branch> branches;
  std::vector<Bifurcation> special;
};

FollowResult follow(const SlowFlowProblem& prob, double mu0, double step) {
  ContinuationSettings s;
  s.p_min = 0.3, s.p_max = 3.0, s.step = step, s.step_max = 5 * step;
  FollowResult r;
  r.branches = continueFrom(prob.system(), singleTicking(prob, mu0), mu0, s);
  for (const Branch& b : r.branches)
    r.special.insert(r.special.end(), b.special.begin(), b.special.end());
  return r;
}

std::vector<double> valuesOf(const FollowResult& r, BifurcationType t) {
  std::vector<double> v;
  for (const Bifurcation& b : r.special)
    if (b.type == t) v.push_back(b.point.p());
  std::sort(v.begin(), v.end());
  return v;
}

TEST(SingleMetronome, FoldAtTheClosedFormMinimumOfMu) {
  const SlowFlowProblem prob([](double mu) { return singleMetronome(mu); }, 3.0, 0);
  const FollowResult r = follow(prob, 3.0, 0.05);
  const auto folds = valuesOf(r, BifurcationType::Fold);
  ASSERT_EQ(folds.size(), 1u);
  const double truth = testing::closedFormFoldMu(kNu);
  EXPECT_NEAR(folds[0], truth, 1e-8) << "independent fold at mu = " << truth;
  EXPECT_LT(worstResidual(prob, r.branches), 1e-12);
}

TEST(SingleMetronome, StuckToStickSlipBorderAtMuEqualToAStar) {
  // at s = 1 beta = 0, so A = A_star (eq. A_star) and mu = A / s = A_star exactly
  const SlowFlowProblem prob([](double mu) { return singleMetronome(mu); }, 3.0, 0);
  const FollowResult r = follow(prob, 3.0, 0.05);
  const double a_star = *steadyAmplitude(kNu, kJ, kThetaC);
  bool found = false;
  for (const Bifurcation& b : r.special)
    if (b.type == BifurcationType::Border && b.point.stable) {
      found = true;
      EXPECT_NEAR(b.point.p(), a_star, 1e-9);
      EXPECT_NEAR(prob.s(b.point.y.head(2), b.point.p()), 1.0, 1e-10);
      EXPECT_FALSE(b.stability_changes);  // a kink: beta is continuous at s = 1
    }
  EXPECT_TRUE(found);
}

TEST(SingleMetronome, IndependentOfStepAndDirection) {
  const SlowFlowProblem prob([](double mu) { return singleMetronome(mu); }, 3.0, 0);
  const auto a = valuesOf(follow(prob, 3.0, 0.05), BifurcationType::Fold);
  const auto b = valuesOf(follow(prob, 3.0, 0.005), BifurcationType::Fold);
  const auto c = valuesOf(follow(prob, 0.9, 0.02), BifurcationType::Fold);  // near the fold
  ASSERT_EQ(a.size(), 1u);
  ASSERT_EQ(b.size(), 1u);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(a[0], b[0], 1e-9);
  EXPECT_NEAR(a[0], c[0], 1e-9);
}

TEST(SingleMetronome, StabilityFromTheAmplitudeEquation) {
  // N = 1: one eigenvalue, d(dA/dtau)/dA at the fixed point (the phase decouples)
  const SlowFlowProblem prob([](double mu) { return singleMetronome(mu); }, 3.0, 0);
  for (double mu : {3.0, 1.5, 0.9}) {
    const Vec x = singleTicking(prob, mu);
    const double A = x(0), h = 1e-6;
    const double slope =
        (amplitudeRate(A + h, (A + h) / mu) - amplitudeRate(A - h, (A - h) / mu)) / (2 * h);
    const Region r = regionAt(prob.system(), x, mu);
    const CVec ev = prob.system().eigenvalues(x, mu, r);
    ASSERT_EQ(ev.size(), 1);
    EXPECT_NEAR(ev(0).real(), slope, 1e-6 * (1 + std::abs(slope))) << "mu " << mu;
  }
}

}  // namespace
}  // namespace metrosync::continuation
