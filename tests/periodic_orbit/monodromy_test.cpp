// The return map's Jacobian (variational equations and saltation matrices) against differences of
// the return map itself (each evaluation a fresh run of the engine), at settled orbits of the
// shipped rigs: one with the platform sticking and slipping, one slipping throughout, and the
// identical pair in phase (simultaneous ticks).
#include <gtest/gtest.h>

#include <cmath>

#include "tests/periodic_orbit/fixtures.h"

namespace metrosync::orbit {
namespace {

// Central differences at h = 1e-5: truncation O(h^2) ~ 1e-10, the return map's noise (~1e-12,
// ReturnSettings::accuracy) over h ~ 1e-7. Measured agreement 4e-10 to 1.3e-8 on these orbits.
constexpr double kStep = 1e-5;
constexpr double kAgree = 1e-6;

Mat differences(const ReturnMap& map, const Vec& u, double period) {
  const int m = u.size();
  Mat J(m, m);
  for (int k = 0; k < m; ++k) {
    Vec a = u, b = u;
    a(k) += kStep;
    b(k) -= kStep;
    J.col(k) = (map.pass(a, period, false).u1 - map.pass(b, period, false).u1) / (2 * kStep);
  }
  return J;
}

// The multipliers as sorted by multipliersOf, matched one by one.
double multiplierDistance(const CVec& a, const CVec& b) {
  double d = 0.0;
  for (int i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a(i) - b(i)));
  return d;
}

struct Case {
  const char* name;
  const char* path;
  int windows_at_least;  // events per period the orbit must have (it is the stick-slip one)
};

class AsymmetricOrbit : public ::testing::TestWithParam<Case> {};

TEST_P(AsymmetricOrbit, JacobianIsTheDifferenceJacobian) {
  const ReturnMap map(testing::shipped(GetParam().path), 0);
  const Orbit o = testing::settledOrbit(map);
  ASSERT_LE(o.residual, 1e-10);
  ASSERT_GE(static_cast<int>(o.pass.windows.size()), GetParam().windows_at_least);
  const Mat fd = differences(map, o.u, o.period);
  EXPECT_LT((o.pass.jacobian - fd).cwiseAbs().maxCoeff(), kAgree) << "\n"
                                                                  << o.pass.jacobian << "\n\n"
                                                                  << fd;
  EXPECT_LT(multiplierDistance(o.multipliers, multipliersOf(fd)), kAgree);
}

INSTANTIATE_TEST_SUITE_P(Rigs, AsymmetricOrbit,
                         ::testing::Values(Case{"f44_alpha02", "yaml/rigs/paper/f4.4-alpha0.2.yaml",
                                                8},
                                           Case{"experiment", "yaml/rigs/experiment.yaml", 6}),
                         [](const ::testing::TestParamInfo<Case>& i) { return i.param.name; });

// Identical metronomes in phase tick at the same instant: a perturbation that makes one tick
// first moves the symmetric part of the return at first order by an amount that depends on which
// one (the return map has a corner on the symmetric orbits). Inputs that keep the symmetry, and
// the multipliers (the antisymmetric inputs' symmetric response lies off the diagonal blocks),
// do not depend on it.
TEST(SymmetricOrbit, MultipliersAndSymmetricColumnsAreTheDifferences) {
  const ReturnMap map(testing::shipped("yaml/rigs/paper/f4.3-mu0.2.yaml"), 0);
  const Orbit o = testing::settledOrbit(map);
  ASSERT_LE(o.residual, 1e-10);
  // u = (xdot, theta_2, thetadot_1, thetadot_2); the orbit is symmetric: theta_2 = theta_1 = 0
  ASSERT_EQ(o.u.size(), 4);
  EXPECT_LT(std::abs(o.u(1)), 1e-10);
  EXPECT_LT(std::abs(o.u(2) - o.u(3)), 1e-10);
  const Mat fd = differences(map, o.u, o.period);
  EXPECT_LT(multiplierDistance(o.multipliers, multipliersOf(fd)), kAgree);
  const Vec sym_v = o.pass.jacobian.col(0), sym_w = o.pass.jacobian.col(2) + o.pass.jacobian.col(3);
  EXPECT_LT((sym_v - fd.col(0)).cwiseAbs().maxCoeff(), kAgree);
  EXPECT_LT((sym_w - fd.col(2) - fd.col(3)).cwiseAbs().maxCoeff(), kAgree);
}

}  // namespace
}  // namespace metrosync::orbit
