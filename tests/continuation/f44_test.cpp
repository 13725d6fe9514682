// The paper's f4.4 family (yaml/rigs/paper/f4.4-alpha4.yaml) in the detuning alpha of metronome
// 2: the locked suppressed state (A_2 small, psi near pi) dies in a saddle-node between alpha =
// 3.9 and 3.95 (the statement, from the paper's sweeps). Checked against direct slow-flow
// runs on both sides of the located fold, and the stability against the polar form's Jacobian.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim/analysis/continuation/derivatives.h"
#include "tests/continuation/fixtures.h"

namespace metrosync::continuation {
namespace {

using testing::f44;
using testing::worstResidual;

struct Family {
  SlowFlowProblem prob{[](double a) { return f44(a); }, 3.9, 0};
  std::vector<Branch> branches;
  Family(double alpha0, double step) {
    const SettledState st = settleFromStart(prob.params(alpha0), 300);
    EXPECT_TRUE(st.settled) << st.why;
    const auto x = solveLocked(prob, prob.pack(st.z, prob.omegaGuess(alpha0, st.z)), alpha0);
    EXPECT_TRUE(x.has_value());
    ContinuationSettings s;
    s.p_min = 3.5, s.p_max = 4.0, s.step = step, s.step_max = 2 * step;
    if (x) branches = continueFrom(prob.system(), *x, alpha0, s);
  }
  std::vector<Bifurcation> folds() const {
    std::vector<Bifurcation> f;
    for (const Branch& b : branches)
      for (const Bifurcation& e : b.special)
        if (e.type == BifurcationType::Fold) f.push_back(e);
    return f;
  }
};

TEST(F44, SaddleNodeBetween3p9And3p95ConfirmedByRuns) {
  const Family fam(3.9, 0.02);
  const auto folds = fam.folds();
  ASSERT_EQ(folds.size(), 1u);
  const double alpha = folds[0].point.p();
  EXPECT_GT(alpha, 3.9);
  EXPECT_LT(alpha, 3.95);
  EXPECT_LT(worstResidual(fam.prob, fam.branches), 1e-12);
  const auto A = fam.prob.amplitudes(folds[0].point.y.head(fam.prob.system().n));
  EXPECT_LT(A[1], 0.9);  // metronome 2 suppressed below its theta_c
  // just below the fold the start settles onto the state; just above it does not
  const SettledState below = settleFromStart(f44(alpha - 0.005), 300);
  ASSERT_TRUE(below.settled) << below.why;
  EXPECT_NEAR(std::abs(below.z[1]), A[1], 0.05);
  const SettledState above = settleFromStart(f44(alpha + 0.02), 300);
  EXPECT_FALSE(above.settled && std::abs(std::abs(above.z[1]) - A[1]) < 0.1) << above.why;
}

TEST(F44, IndependentOfStepAndDirection) {
  const Family coarse(3.9, 0.03), fine(3.9, 0.004), from_below(3.7, 0.02);
  ASSERT_EQ(coarse.folds().size(), 1u);
  ASSERT_EQ(fine.folds().size(), 1u);
  ASSERT_EQ(from_below.folds().size(), 1u);
  EXPECT_NEAR(coarse.folds()[0].point.p(), fine.folds()[0].point.p(), 1e-9);
  EXPECT_NEAR(coarse.folds()[0].point.p(), from_below.folds()[0].point.p(), 1e-9);
}

// The reduced polar flow (A_1, A_2, psi = phi_1 - phi_2) from models/slow_flow.h's polar rates:
// an independent route to the same eigenvalues (away from the borders).
CVec polarEigenvalues(const ScaledParams& p, const std::vector<double>& A, double psi) {
  auto f = [&p](const Vec& y) {
    const SlowFlowPolarRates r = slowFlowPolarRates(p, {y(0), y(1)}, {0.0, -y(2)});
    Vec out(3);
    out << r.dA[0], r.dA[1], r.dphi[0] - r.dphi[1];
    return out;
  };
  Vec y(3);
  y << A[0], A[1], psi;
  return jacobianOf(f, y).eigenvalues();
}

void sortEigen(CVec& v) {
  std::sort(v.data(), v.data() + v.size(), [](const auto& a, const auto& b) {
    return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag();
  });
}

TEST(F44, EigenvaluesAgreeWithThePolarJacobian) {
  const Family fam(3.9, 0.02);
  ASSERT_FALSE(fam.branches.empty());
  int checked = 0;
  for (const BranchPoint& q : fam.branches[0].points) {
    const Vec x = q.y.head(fam.prob.system().n);
    CVec mine = q.eigenvalues;
    CVec theirs = polarEigenvalues(fam.prob.params(q.p()), fam.prob.amplitudes(x),
                                   fam.prob.phaseDifferences(x)[0]);
    sortEigen(mine);
    sortEigen(theirs);
    ASSERT_EQ(mine.size(), theirs.size());
    // both by central differences (~1e-9); 1e-6 leaves room near the fold's small eigenvalue
    for (int i = 0; i < mine.size(); ++i)
      EXPECT_LT(std::abs(mine(i) - theirs(i)), 1e-6) << "alpha " << q.p();
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

}  // namespace
}  // namespace metrosync::continuation
