// The ODE toolkit's Runge-Kutta pairs (sim/ode, used by the direct engine and the slow flow)
// against the theory they come from: the order conditions of the tables (a typo in one of the ~400
// coefficients breaks one of them), the observed order of the solution, of the error estimate and
// of the interpolant on a nonlinear problem with a known solution, and the root bracketing the
// events rely on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <string>
#include <vector>

#include "sim/engines/direct/direct_engine.h"
#include "sim/ode/rk_stepper.h"
#include "sim/ode/rk_tableau.h"
#include "sim/ode/root_find.h"

namespace metrosync::ode {
namespace {

// every tableau sim/ode provides
const std::vector<std::string> kMethods = {"dopri5", "verner65", "verner76"};

TEST(RkTableau, EveryDirectEngineIntegratorIsATestedTableau) {
  for (const std::string& name : metrosync::directIntegratorNames())
    EXPECT_NE(std::find(kMethods.begin(), kMethods.end(), name), kMethods.end()) << name;
}

// Row sums of a, the quadrature conditions sum_j b_j c_j^k = 1/(k+1) for k < order (and for the
// embedded weights b - e up to error_order), the interpolant's end value (p at th = 1 is b) and
// the first bushy-tree condition sum_j b_j a_jl c_l = 1/6. These are necessary conditions only,
// but each coefficient enters several of them.
TEST(RkTableau, SatisfiesItsOrderConditions) {
  for (const std::string& name : kMethods) {
    const RkTableau& t = rkTableau(name);
    ASSERT_EQ(t.name, name);
    ASSERT_GE(t.dense_stages, t.stages);
    // 1e-13: the tables hold up to 40 digits, rounded to doubles, and Verner's largest
    // coefficients are ~1e5 (rounding 1e-11 absolute, cancelling in the sums)
    const double tol = 1e-11;
    for (int j = 0; j < t.dense_stages; ++j) {
      double sum = 0;
      for (int l = 0; l < j; ++l) sum += t.a[j][l];
      EXPECT_NEAR(sum, t.c[j], tol) << name << " row " << j;
    }
    for (int k = 0; k < t.order; ++k) {
      double sb = 0, sbh = 0;
      for (int j = 0; j < t.stages; ++j) {
        sb += t.b[j] * std::pow(t.c[j], k);
        sbh += (t.b[j] - t.e[j]) * std::pow(t.c[j], k);
      }
      EXPECT_NEAR(sb, 1.0 / (k + 1), tol) << name << " b, k = " << k;
      if (k < t.error_order) {
        EXPECT_NEAR(sbh, 1.0 / (k + 1), tol) << name << " b-hat, k = " << k;
      }
    }
    double third = 0;
    for (int j = 0; j < t.stages; ++j)
      for (int l = 0; l < j; ++l) third += t.b[j] * t.a[j][l] * t.c[l];
    EXPECT_NEAR(third, 1.0 / 6, tol) << name;
    for (int j = 0; j < t.dense_stages; ++j) {
      double at_one = 0;
      for (int q = 0; q < t.dense_degree; ++q) at_one += t.p[j][q];
      EXPECT_NEAR(at_one, j < t.stages ? t.b[j] : 0.0, tol) << name << " p at th = 1, j = " << j;
    }
    // FSAL: the last stage is f(t1, y1)
    EXPECT_EQ(t.c[t.stages - 1], 1.0) << name;
  }
}

// The pendulum theta'' = -sin(theta) from theta = 2 at rest, integrated with a fixed step h to
// t = 5.3 (not a multiple of the period, where a periodic orbit's errors can cancel to a higher
// order): halving h must divide the global error by ~2^order, and the first step's error estimate
// by ~2^(error_order + 1). The reference is the same problem in 20000 verner76 steps.
struct Pendulum : OdeRhs {
  void eval(const double* y, double* dy) override {
    dy[0] = y[1];
    dy[1] = -std::sin(y[0]);
  }
};

constexpr double kEnd = 5.3;

struct StepResult {
  double y[2] = {0, 0};
  double estimate = 0.0;  // the error estimate of the first step
};

StepResult runFixedSteps(const RkTableau& tab, int n_steps) {
  Pendulum f;
  RkStepper st(tab, 2, f);
  st.setTolerances(1.0, {1.0, 1.0});  // the norm is then |err| / (1 + max|y|)
  const double y0[2] = {2.0, 0.0};
  st.restart(0.0, y0);
  StepResult r;
  for (int k = 0; k < n_steps; ++k) {
    const double err = st.attempt(kEnd / n_steps);
    if (k == 0) r.estimate = err;
    st.advance();
  }
  r.y[0] = st.y()[0];
  r.y[1] = st.y()[1];
  return r;
}

TEST(RkStepper, ConvergesAtTheMethodsOrder) {
  const StepResult ref = runFixedSteps(rkTableau("verner76"), 20000);
  for (const std::string& name : kMethods) {
    const RkTableau& t = rkTableau(name);
    const StepResult coarse = runFixedSteps(t, 20), fine = runFixedSteps(t, 40);
    const double e_coarse = std::hypot(coarse.y[0] - ref.y[0], coarse.y[1] - ref.y[1]);
    const double e_fine = std::hypot(fine.y[0] - ref.y[0], fine.y[1] - ref.y[1]);
    const double observed = std::log2(e_coarse / e_fine);
    // the asymptotic ratio is 2^order. These pairs are tuned to make their leading error term
    // small, so at 20-40 steps the next terms still show and the observed order comes out up to
    // ~1.5 higher (measured: 5.6, 6.9, 8.5); a wrong coefficient drops it to 1-4
    EXPECT_GT(observed, t.order - 0.5) << name << ": errors " << e_coarse << ", " << e_fine;
    EXPECT_LT(observed, t.order + 2.0) << name << ": errors " << e_coarse << ", " << e_fine;
    const double est = std::log2(coarse.estimate / fine.estimate);
    EXPECT_GT(est, t.error_order + 0.3) << name;  // measured 6.4 for verner76 (nominal 7)
    EXPECT_LT(est, t.error_order + 3.0) << name;
  }
}

// The interpolant at mid-step against the same problem integrated to that time exactly (a fine
// run that lands on it); its local error is O(h^(degree+1)) for these interpolants, so halving h
// divides it by ~2^(degree+1) (dopri5: 2^5, verner65: 2^7, verner76: 2^8).
TEST(RkStepper, InterpolantHasItsOrder) {
  for (const std::string& name : kMethods) {
    const RkTableau& t = rkTableau(name);
    Pendulum f;
    double errs[2];
    for (int pass = 0; pass < 2; ++pass) {
      const double h = pass == 0 ? 0.4 : 0.2;
      RkStepper st(t, 2, f);
      st.setTolerances(1.0, {1.0, 1.0});
      const double y0[2] = {2.0, 0.0};
      st.restart(0.0, y0);
      st.attempt(h);
      double mid[2];
      st.interpolate(0.37, mid);
      // reference: 2000 verner76 steps to 0.37 h
      RkStepper ref(rkTableau("verner76"), 2, f);
      ref.restart(0.0, y0);
      for (int k = 0; k < 2000; ++k) {
        ref.attempt(0.37 * h / 2000);
        ref.advance();
      }
      errs[pass] = std::hypot(mid[0] - ref.y()[0], mid[1] - ref.y()[1]);
      // the interpolant's rate is the derivative of its value (checked by a central difference)
      const double d = 1e-6;
      const double fd = (st.component(0, 0.37 + d) - st.component(0, 0.37 - d)) / (2 * d * h);
      EXPECT_NEAR(st.componentRate(0, 0.37), fd, 1e-7) << name;
    }
    const double observed = std::log2(errs[0] / errs[1]);
    // the local error of an interpolant of order q is O(h^(q+1)); dopri5's quartic is 4th order,
    // Verner's are of the pair's order (6, 7). At a single point inside one step the leading
    // term can vanish (verner65 shows 8 at th = 0.37), so this bound is one-sided: a wrong
    // coefficient gives order 1-3.
    const int expected = name == "dopri5" ? 5 : t.order + 1;
    EXPECT_GT(observed, expected - 0.7) << name << ": errors " << errs[0] << ", " << errs[1];
  }
}

// Two pendulums side by side (dimension 4): the engine's witnesses read one component of the
// interpolant (component), the event starts from the whole state (interpolate), the envelope
// samples read a range (interpolateRange); all three must agree to the last bit.
struct TwoPendulums : OdeRhs {
  void eval(const double* y, double* dy) override {
    dy[0] = y[2];
    dy[1] = y[3];
    dy[2] = -std::sin(y[0]);
    dy[3] = -2.0 * std::sin(y[1]) - 0.1 * y[3];
  }
};

TEST(RkStepper, ComponentRangeAndWholeStateInterpolantsAgreeBitForBit) {
  for (const std::string& name : kMethods) {
    TwoPendulums f;
    RkStepper st(rkTableau(name), 4, f);
    st.setTolerances(1e-6, {1e-6, 1e-6, 1e-6, 1e-6});
    const double y0[4] = {2.0, -0.5, 0.0, 0.3};
    st.restart(0.0, y0);
    st.attempt(0.3);
    for (double th : {0.0, 0.013, 0.37, 0.5, 0.999, 1.0}) {
      double whole[4], range[4] = {-7, -7, -7, -7};
      st.interpolate(th, whole);
      st.interpolateRange(th, 1, 2, range);
      for (int k = 0; k < 4; ++k) EXPECT_EQ(st.component(k, th), whole[k]) << name << " " << k;
      EXPECT_EQ(range[1], whole[1]) << name << " th " << th;
      EXPECT_EQ(range[2], whole[2]) << name << " th " << th;
      EXPECT_EQ(range[0], -7.0) << name << ": written outside the range";
      EXPECT_EQ(range[3], -7.0) << name << ": written outside the range";
    }
    // and the interpolant is not trivially the start state: at th = 1 it is the step's end
    EXPECT_NE(st.component(0, 0.5), y0[0]);
  }
}

TEST(RkStepper, InitialStepSizeIsAcceptedAndScalesWithTheTolerance) {
  // Hairer's starting step aims at a local error ~ 0.01 of the target: the first attempt must be
  // accepted, and a 1e5 times tighter tolerance must shrink it by about 1e5^(1/(order+1)) ..
  // 1e5^(1/order) (the estimate uses the order; 3x slack either way)
  for (const std::string& name : kMethods) {
    const RkTableau& t = rkTableau(name);
    Pendulum f;
    RkStepper st(t, 2, f);
    const double y0[2] = {1.2, 0.3};
    double h[2];
    const double rtol[2] = {1e-6, 1e-11};
    for (int k = 0; k < 2; ++k) {
      st.setTolerances(rtol[k], {rtol[k], rtol[k]});
      st.restart(0.0, y0);
      h[k] = st.initialStepSize(10.0);
      EXPECT_GT(h[k], 0.0) << name;
      EXPECT_LE(st.attempt(h[k]), 1.0) << name << " rtol " << rtol[k];
    }
    const double ratio = h[0] / h[1];
    EXPECT_GT(ratio, std::pow(1e5, 1.0 / (t.order + 1)) / 3) << name;
    EXPECT_LT(ratio, std::pow(1e5, 1.0 / t.order) * 3) << name;
    st.restart(0.0, y0);
    EXPECT_LE(st.initialStepSize(1e-3), 1e-3) << name;  // never beyond h_max
  }
}

TEST(RootFind, BracketsToAFewUlpsWithTheRootBelowTheUpperEnd) {
  // a cubic with a root at an irrational point, and a root at the very end of the interval
  auto f = [](double x) { return (x - M_SQRT1_2) * (1 + x * x) * 3.0; };
  const Bracket b = illinois(f, 0.0, f(0.0), 1.0, f(1.0));
  EXPECT_LT(f(b.lo), 0.0);
  EXPECT_GE(f(b.hi), 0.0);
  EXPECT_LE(b.hi - b.lo, 4 * DBL_EPSILON);
  EXPECT_LE(b.lo, M_SQRT1_2);
  EXPECT_GE(b.hi, M_SQRT1_2);
  // a flat, ill-conditioned root (multiplicity 3): still a valid bracket, no endless loop
  auto g = [](double x) { return std::pow(x - 0.3, 3); };
  const Bracket c = illinois(g, 0.0, g(0.0), 1.0, g(1.0));
  EXPECT_LT(g(c.lo), 0.0);
  EXPECT_GE(g(c.hi), 0.0);
  EXPECT_NEAR(0.5 * (c.lo + c.hi), 0.3, 1e-5);  // cube root of rounding: ~1e-5.3
}

}  // namespace
}  // namespace metrosync::ode
