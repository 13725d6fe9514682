// Two-parameter continuation of a Hopf point (the bialternate-product system of fold_curve.h):
// the in-phase state of the paper's identical pair (f4.3) loses stability at a subcritical Hopf
// point near mu = 0.289; its curve in (mu, nu) is checked point by point against one-parameter
// continuations in mu at that nu, which locate the Hopf point independently (regula falsi on the
// product of eigenvalue sums along a branch, test_functions.h), and against the eigenvalues there.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "sim/analysis/continuation/fold_curve.h"
#include "tests/continuation/fixtures.h"
#include "yaml/rig_loader.h"

namespace metrosync::continuation {
namespace {

ScaledParams f43(double mu, double nu) {
  const std::string path = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/paper/f4.3-mu0.2.yaml";
  char a[64], b[64], c[64];
  std::snprintf(a, sizeof a, "platform.friction.mu=%.17g", mu);
  std::snprintf(b, sizeof b, "metronomes.0.nu=%.17g", nu);
  std::snprintf(c, sizeof c, "metronomes.1.nu=%.17g", nu);
  return computeScaled(loadRigFile(path, {a, b, c}));
}

// The Hopf points of the branch through the locked state (A, psi) at mu0, nu, over mu in [lo, hi].
std::vector<Bifurcation> hopfPoints(double nu, const std::vector<double>& A,
                                    const std::vector<double>& psi, double mu0, double lo,
                                    double hi) {
  const SlowFlowProblem prob([nu](double mu) { return f43(mu, nu); }, mu0, 0);
  const auto z = stateFrom(A, psi);
  const auto x = solveLocked(prob, prob.pack(z, prob.omegaGuess(mu0, z)), mu0);
  EXPECT_TRUE(x.has_value());
  if (!x) return {};
  ContinuationSettings s;
  s.p_min = lo, s.p_max = hi, s.step = 0.002, s.step_max = 0.01, s.max_branches = 1;
  std::vector<Bifurcation> h;
  for (const Branch& b : continueFrom(prob.system(), *x, mu0, s))
    for (const Bifurcation& e : b.special)
      if (e.type == BifurcationType::Hopf) h.push_back(e);
  return h;
}

TEST(HopfCurve, InPhaseHopfInMuAndNuAgreesWithOneParameterLocations) {
  constexpr double kNu = 0.7;
  // the in-phase state at mu = 0.25 (A = 1.6, psi = 0 is close: Newton finishes it)
  const auto h = hopfPoints(kNu, {1.6, 1.6}, {0.0}, 0.25, 0.2, 0.35);
  ASSERT_EQ(h.size(), 1u);
  EXPECT_NEAR(h[0].point.p(), 0.2891, 1e-3);  // the value `continue` reports (docs)
  const SlowFlowProblem prob([](double mu) { return f43(mu, kNu); }, h[0].point.p(), 0);
  ContinuationSettings s;
  s.p_min = 0.6, s.p_max = 0.8, s.step = 0.005, s.step_max = 0.02;
  const int n = prob.system().n;
  const FoldCurve curve =
      continueHopf(f43, 0, h[0].point.y.head(n), h[0].point.p(), kNu, h[0].point.region, s);
  EXPECT_EQ(curve.kind, CurveKind::Hopf);
  ASSERT_GT(curve.points.size(), 6u) << curve.end_backward << " / " << curve.end_forward;
  double nu_lo = 1, nu_hi = 0;
  for (size_t k = 0; k < curve.points.size(); k += curve.points.size() / 4) {
    const FoldCurvePoint& q = curve.points[k];
    const auto one = hopfPoints(q.p2, q.A, q.psi, q.p1 - 0.005, q.p1 - 0.01, q.p1 + 0.01);
    ASSERT_EQ(one.size(), 1u) << "nu " << q.p2;
    EXPECT_NEAR(one[0].point.p(), q.p1, 1e-7) << "nu " << q.p2;
    EXPECT_NEAR(std::abs(one[0].point.eigenvalues(0).imag()) +
                    std::abs(one[0].point.eigenvalues(1).imag()) +
                    std::abs(one[0].point.eigenvalues(2).imag()),
                2 * q.frequency, 1e-5)
        << "the pair's frequency, nu " << q.p2;
  }
  for (const auto& q : curve.points) nu_lo = std::min(nu_lo, q.p2), nu_hi = std::max(nu_hi, q.p2);
  EXPECT_LT(nu_lo, 0.65);  // both ways from nu = 0.7
  EXPECT_GT(nu_hi, 0.75);
}

}  // namespace
}  // namespace metrosync::continuation
