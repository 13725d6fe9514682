// The closed-form derivatives of sim/analysis/periodic_orbit/scaled_model.h against central
// differences of the engine's own equations, in every platform mode, on states of a physical and
// a scaled rig (random, seeded).
#include <gtest/gtest.h>

#include <random>

#include "tests/periodic_orbit/fixtures.h"

namespace metrosync::orbit {
namespace {

// Central differences of a function of z with step h in every component: error O(h^2) ~ 1e-10
// of O(1) derivatives at h = 1e-5 (scaled units), rounding O(1e-16 / h) ~ 1e-11.
constexpr double kStep = 1e-5;
constexpr double kAgree = 1e-7;

template <class F>
Mat differences(F&& f, const Vec& z) {
  const int d = z.size();
  Mat J(f(z).size(), d);
  for (int k = 0; k < d; ++k) {
    Vec a = z, b = z;
    a(k) += kStep;
    b(k) -= kStep;
    J.col(k) = (f(a) - f(b)) / (2 * kStep);
  }
  return J;
}

Vec randomState(const ScaledModel& m, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  Vec z(m.dim());
  for (int k = 0; k < m.dim(); ++k) z(k) = u(rng);
  return z;
}

std::vector<Rig> rigs() {
  return {testing::shipped("yaml/rigs/experiment.yaml"),
          testing::shipped("yaml/rigs/paper/f4.4-alpha2.yaml"),
          testing::shipped("yaml/rigs/experiment.yaml", {"platform.spring={k: 30.0}"}),
          testing::shipped("yaml/rigs/paper/f4.3-mu0.2.yaml",
                           {"platform.friction={law: viscous, c: 0.3}"})};
}

TEST(ScaledModel, JacobianOfTheRhsInEveryMode) {
  std::mt19937 rng(26);
  for (const Rig& rig : rigs()) {
    const ScaledModel m(rig);
    for (int trial = 0; trial < 5; ++trial) {
      const Vec z = randomState(m, rng);
      for (PlatformMode mode :
           {PlatformMode::Stuck, PlatformMode::SlipPositive, PlatformMode::SlipNegative}) {
        const Mat fd = differences([&](const Vec& y) { return m.rhs(y, mode); }, z);
        const Mat J = m.jacobian(z, mode);
        EXPECT_LT((J - fd).cwiseAbs().maxCoeff(), kAgree * std::max(1.0, fd.cwiseAbs().maxCoeff()))
            << rig.name << " mode " << static_cast<int>(mode);
      }
    }
  }
}

TEST(ScaledModel, HoldingForceGradient) {
  std::mt19937 rng(7);
  for (const Rig& rig : rigs()) {
    const ScaledModel m(rig);
    for (int trial = 0; trial < 5; ++trial) {
      Vec z = randomState(m, rng);
      z(ScaledModel::kV) = 0.0;
      const Mat fd =
          differences([&](const Vec& y) { return Vec::Constant(1, m.holdingForce(y)); }, z);
      Vec g = fd.row(0).transpose();
      g(ScaledModel::kV) = 0.0;
      EXPECT_LT((m.holdingForceGradient(z) - g).cwiseAbs().maxCoeff(),
                kAgree * std::max(1.0, g.cwiseAbs().maxCoeff()))
          << rig.name;
    }
  }
}

TEST(ScaledModel, JumpMapJacobians) {
  std::mt19937 rng(11);
  for (const Rig& rig : rigs()) {
    const ScaledModel m(rig);
    for (int trial = 0; trial < 5; ++trial) {
      const Vec z = randomState(m, rng);
      for (const std::vector<int>& ticked : {std::vector<int>{0}, std::vector<int>{0, 1}}) {
        const Mat fd = differences([&](const Vec& y) { return m.tick(y, ticked); }, z);
        EXPECT_LT((m.tickJacobian(z, ticked) - fd).cwiseAbs().maxCoeff(), kAgree) << rig.name;
      }
      if (!m.hasPlatform()) continue;
      const Mat fd = differences([&](const Vec& y) { return m.plasticStop(y); }, z);
      EXPECT_LT((m.plasticStopJacobian(z) - fd).cwiseAbs().maxCoeff(), kAgree) << rig.name;
    }
  }
}

TEST(ScaledModel, ConversionsRoundTrip) {
  for (const Rig& rig : rigs()) {
    const ScaledModel m(rig);
    std::mt19937 rng(3);
    const Vec z = randomState(m, rng);
    Rig r = rig;
    m.setStart(r, z);
    // the engine's row format from the rig's start: t, x, xdot, theta_i, thetadot_i, platform
    const ScaledParams& sp = m.scaled();
    const bool scaled = rig.units == Units::Scaled;
    const double ts = scaled ? 1.0 / sp.time_scale_s : 1.0;
    std::vector<double> row = {0.0, r.platform.start_x_m / (scaled ? sp.x_scale_m : 1.0),
                               r.platform.start_v_m_s / (scaled ? sp.x_scale_m : 1.0) / ts};
    for (const MetronomeSpec& s : r.metronomes) {
      row.push_back(s.start_angle_rad / (scaled ? sp.angle_scale : 1.0));
      row.push_back(s.start_rate_rad_s / (scaled ? sp.angle_scale : 1.0) / ts);
    }
    row.push_back(0.0);
    EXPECT_LT((m.stateFromRow(row) - z).cwiseAbs().maxCoeff(), 1e-13) << rig.name;
  }
}

}  // namespace
}  // namespace metrosync::orbit
