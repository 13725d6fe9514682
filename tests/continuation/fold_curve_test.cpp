// Two-parameter continuation of a fold: the single metronome's fold in mu followed in its damping
// nu; every point of the curve must sit on the closed-form fold mu*(nu) (fixtures.h), found
// independently for each nu (the local minimum of mu along the amplitude equation's curve).
#include "sim/analysis/continuation/fold_curve.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/continuation/fixtures.h"

namespace metrosync::continuation {
namespace {

using testing::closedFormFoldMu;
using testing::singleMetronome;
using testing::singleTicking;

ScaledParams withNu(double mu, double nu) {
  ScaledParams p = singleMetronome(mu);
  p.nu = {nu};
  p.A_star = {steadyAmplitude(nu, p.J[0], p.theta_c[0])};
  return p;
}

TEST(FoldCurve, SingleMetronomeFoldInMuAndNu) {
  const SlowFlowProblem prob([](double mu) { return withNu(mu, 0.7); }, 3.0, 0);
  ContinuationSettings s;
  s.p_min = 0.3, s.p_max = 3.0, s.step = 0.05, s.step_max = 0.2;
  const auto branches = continueFrom(prob.system(), singleTicking(prob, 3.0), 3.0, s);
  const Bifurcation* fold = nullptr;
  for (const Bifurcation& b : branches[0].special)
    if (b.type == BifurcationType::Fold) fold = &b;
  ASSERT_NE(fold, nullptr);
  ContinuationSettings s2;
  s2.p_min = 0.6, s2.p_max = 0.8, s2.step = 0.005, s2.step_max = 0.02;
  const FoldCurve curve =
      continueFold(withNu, 0, fold->point.y.head(2), fold->point.p(), 0.7, fold->point.region, s2);
  ASSERT_GT(curve.points.size(), 5u) << curve.end_backward << " / " << curve.end_forward;
  double nu_lo = 1, nu_hi = 0;
  for (size_t k = 0; k < curve.points.size(); k += 3) {
    const FoldCurvePoint& q = curve.points[k];
    // the local minimum of mu near this fold's s = A / mu (elsewhere the curve has others)
    const double s_fold = q.A[0] / q.p1;
    EXPECT_NEAR(q.p1, closedFormFoldMu(q.p2, s_fold - 0.1, s_fold + 0.1), 1e-8) << "nu " << q.p2;
    nu_lo = std::min(nu_lo, q.p2), nu_hi = std::max(nu_hi, q.p2);
  }
  EXPECT_LT(nu_lo, 0.65);  // it went both ways from nu = 0.7
  EXPECT_GT(nu_hi, 0.75);
}

}  // namespace
}  // namespace metrosync::continuation
