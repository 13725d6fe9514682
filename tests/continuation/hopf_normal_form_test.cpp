// The continuation core on a textbook system: the Hopf normal form (Kuznetsov eq. 3.18), its
// equilibrium moved with the parameter so that the branch is not trivial,
//   u = x + b^2, v = y - b:  x' = b x - y + s x r^2,  y' = x + b y + s y r^2,  r^2 = x^2 + y^2.
// Truth: a Hopf point at b = 0 with eigenvalues b +- i; there q = (1, -i)/sqrt(2) (|q| = 1),
// B = 0 and C(u, v, w) = 2 s [u (v.w) + v (u.w) + w (u.v)], so C(q, q, qbar) = 4 s q (q.q = 0,
// q.qbar = 1) and Kuznetsov's l1 = Re <p, 4 s q> / (2 w) = 2 s.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/analysis/continuation/arclength.h"
#include "sim/analysis/continuation/derivatives.h"
#include "sim/analysis/continuation/lyapunov.h"

namespace metrosync::continuation {
namespace {

ContinuationSystem normalForm(double sigma) {
  ContinuationSystem sys;
  sys.n = 2;
  auto field = [sigma](const Vec& u, double b) {
    const double x = u(0) - b * b, y = u(1) + b, r2 = x * x + y * y;
    Vec f(2);
    f << b * x - y + sigma * x * r2, x + b * y + sigma * y * r2;
    return f;
  };
  sys.residual = [field](const Vec& u, double b, const Region&) { return field(u, b); };
  sys.eigenvalues = [field](const Vec& u, double b, const Region&) {
    return CVec(jacobianOf([&](const Vec& w) { return field(w, b); }, u).eigenvalues());
  };
  sys.lyapunov = [field](const Vec& u, double b, const Region&) {
    return firstLyapunovCoefficient([&](const Vec& w) { return field(w, b); }, u);
  };
  return sys;
}

std::vector<Bifurcation> hopfPoints(const std::vector<Branch>& branches) {
  std::vector<Bifurcation> h;
  for (const Branch& b : branches)
    for (const Bifurcation& e : b.special)
      if (e.type == BifurcationType::Hopf) h.push_back(e);
  return h;
}

TEST(HopfNormalForm, LocatedAtZeroWithItsLyapunovCoefficient) {
  for (double sigma : {-1.0, 1.0, -0.25}) {
    ContinuationSettings s;
    s.p_min = -1.0, s.p_max = 1.0, s.step = 0.07, s.step_max = 0.2;
    const double b0 = -0.8;
    Vec u0(2);
    u0 << 0.3 + b0 * b0, -b0 - 0.2;  // off the equilibrium: Newton has work to do
    const auto branches = continueFrom(normalForm(sigma), u0, b0, s);
    const auto h = hopfPoints(branches);
    ASSERT_EQ(h.size(), 1u) << "sigma " << sigma;
    EXPECT_NEAR(h[0].point.p(), 0.0, 1e-8);
    EXPECT_NEAR(h[0].point.y(0), 0.0, 1e-8);  // u = b^2 at b = 0
    EXPECT_NEAR(std::abs(h[0].point.eigenvalues(0).imag()), 1.0, 1e-6);
    // B and C by differences of steps 1e-4 and 1e-3: ~1e-6 relative
    EXPECT_NEAR(h[0].lyapunov, 2 * sigma, 1e-5 * std::abs(sigma) + 1e-6);
    EXPECT_TRUE(h[0].stability_changes);
    // the branch: stable for b < 0, unstable for b > 0
    for (const BranchPoint& q : branches[0].points)
      if (std::abs(q.p()) > 1e-6) {
        EXPECT_EQ(q.stable, q.p() < 0) << q.p();
      }
  }
}

}  // namespace
}  // namespace metrosync::continuation
