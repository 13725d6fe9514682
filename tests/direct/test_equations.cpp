// The direct engine's equations (models/network_equations.h, a single board) against an independent
// formulation: the full mass matrix [[M, c^T], [c, diag(I)]] and Lagrange's equations written out
// densely and solved by Eigen, on random rigs and states (property tests, Pinocchio style). The
// O(N) Schur solves must give the same accelerations, holding force and tick impulses.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "models/network_equations.h"

namespace metrosync::network {
namespace {

constexpr int kX = 0, kV = 1;  // a single board's x and xdot (models/network_layout.h)

struct RandomCase {
  Rig rig;
  std::vector<double> y;  // the engine's state layout
};

enum class Law { Coulomb, Viscous, None };

RandomCase makeCase(std::mt19937& rng, int n, Law law) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  RandomCase rc;
  Rig& rig = rc.rig;
  rig.gravity_m_s2 = 9.81;
  rig.platform.mass_kg = 0.05 + 0.3 * u(rng);
  const double mu_bar = 1e-3 * u(rng), c_bar = 0.1 * u(rng);
  rig.platform.friction = law == Law::Coulomb   ? FrictionLaw::coulomb(mu_bar)
                          : law == Law::Viscous ? FrictionLaw::viscous(c_bar)
                                                : FrictionLaw::none();
  rig.platform.spring_N_m = 20 * u(rng);
  for (int i = 0; i < n; ++i) {
    MetronomeSpec m;
    m.box_mass_kg = 0.05 * u(rng);
    m.pendulum_mass_kg = 0.01 + 0.03 * u(rng);
    m.length_m = 0.01 + 0.03 * u(rng);
    m.inertia_kgm2 = m.pendulum_mass_kg * m.length_m * m.length_m * (1 + u(rng));
    m.damping_kg_s = 0.05 * u(rng);
    m.theta_c_rad = 0.2;
    m.impulse_Nms = 1e-5 * (1 + u(rng));
    m.locked = n > 1 && i == n - 1 && u(rng) < 0.5;  // sometimes a locked one
    rig.metronomes.push_back(m);
  }
  NetworkEquations eq(rig);
  rc.y.assign(eq.layout().dim(), 0.0);
  rc.y[kX] = 0.01 * (u(rng) - 0.5);
  rc.y[kV] = 0.1 * (u(rng) - 0.5);
  for (int j = 0; j < eq.numSwinging(); ++j) {
    rc.y[eq.layout().theta(j)] = 2.0 * (u(rng) - 0.5);
    rc.y[eq.layout().omega(j)] = 10.0 * (u(rng) - 0.5);
  }
  return rc;
}

// Lagrange's equations of e1.1 with the dense mass matrix: M(q) qddot = Q(q, qdot) + friction,
// q = (x, theta_1..theta_n); the platform row gets `friction` (unknown when held still).
struct Dense {
  Eigen::MatrixXd M;
  Eigen::VectorXd Q;
};

Dense dense(const NetworkEquations& eq, const Rig& rig, const std::vector<double>& y) {
  const int n = eq.numSwinging();
  Dense d;
  d.M = Eigen::MatrixXd::Zero(n + 1, n + 1);
  d.Q = Eigen::VectorXd::Zero(n + 1);
  d.M(0, 0) = rig.totalMass();
  d.Q(0) = -rig.platform.spring_N_m * y[0] - rig.platform.friction.valueOr("c", 0.0) * y[1];
  int j = 0;
  for (const MetronomeSpec& m : rig.metronomes) {
    if (m.locked) continue;
    const double th = y[eq.layout().theta(j)], w = y[eq.layout().omega(j)];
    const double mL = m.pendulum_mass_kg * m.length_m;
    d.M(0, j + 1) = d.M(j + 1, 0) = mL * std::cos(th);
    d.M(j + 1, j + 1) = m.inertia_kgm2;
    d.Q(0) += mL * std::sin(th) * w * w;  // centripetal term of e1.1c
    d.Q(j + 1) =
        -mL * rig.gravity_m_s2 * std::sin(th) - m.damping_kg_s * m.length_m * m.length_m * w;
    ++j;
  }
  return d;
}

TEST(DirectEquations, SchurSolveMatchesTheDenseMassMatrix) {
  std::mt19937 rng(12345);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 7;
    const Law law = static_cast<Law>(trial % 3);  // Coulomb, Viscous, None
    RandomCase rc = makeCase(rng, n, law);
    NetworkEquations eq(rc.rig);
    const Dense d = dense(eq, rc.rig, rc.y);
    for (PlatformMode mode : {PlatformMode::SlipPositive, PlatformMode::SlipNegative}) {
      std::vector<double> dy(rc.y.size());
      eq.rhs(rc.y.data(), mode, dy.data());
      Eigen::VectorXd rhs = d.Q;
      const double bound =
          rc.rig.platform.friction.valueOr("mu", 0.0) * rc.rig.totalMass() * rc.rig.gravity_m_s2;
      if (law == Law::Coulomb) rhs(0) += -bound * static_cast<int>(mode);
      const Eigen::VectorXd qdd = d.M.ldlt().solve(rhs);
      // relative to the size of the accelerations: the two solves differ by rounding only
      const double scale = 1.0 + qdd.cwiseAbs().maxCoeff();
      EXPECT_NEAR(dy[kV], qdd(0), 1e-12 * scale) << "trial " << trial;
      for (int j = 0; j < eq.numSwinging(); ++j)
        EXPECT_NEAR(dy[eq.layout().omega(j)], qdd(j + 1), 1e-12 * scale) << "trial " << trial;
    }
    // held still (Coulomb stuck): xddot = 0, and friction supplies the platform row's residual
    if (law == Law::Coulomb) {
      std::vector<double> ys = rc.y, dy(rc.y.size());
      ys[kV] = 0.0;
      eq.rhs(ys.data(), PlatformMode::Stuck, dy.data());
      EXPECT_EQ(dy[kV], 0.0);
      EXPECT_EQ(dy[kX], 0.0);
      const Dense ds = dense(eq, rc.rig, ys);
      Eigen::VectorXd thdd(eq.numSwinging());
      for (int j = 0; j < eq.numSwinging(); ++j) thdd(j) = dy[eq.layout().omega(j)];
      // pendulum rows with xddot = 0: I thetaddot = Q
      for (int j = 0; j < eq.numSwinging(); ++j)
        EXPECT_NEAR(ds.M(j + 1, j + 1) * thdd(j), ds.Q(j + 1), 1e-12 * (1 + std::abs(ds.Q(j + 1))));
      // platform row: sum_j c_j thetaddot_j = Q_0 + F  =>  F = H
      const double F = ds.M.row(0).tail(eq.numSwinging()).dot(thdd) - ds.Q(0);
      EXPECT_NEAR(eq.holdingForce(ys.data()), F, 1e-12 * (1 + std::abs(F))) << "trial " << trial;
      // and its rate: a central difference along the held motion
      const double h = 1e-6;
      std::vector<double> yp = ys, ym = ys;
      for (size_t k = 0; k < ys.size(); ++k) {
        yp[k] += h * dy[k];
        ym[k] -= h * dy[k];
      }
      const double fd = (eq.holdingForce(yp.data()) - eq.holdingForce(ym.data())) / (2 * h);
      // truncation O(h^2 * third derivative) ~ 1e-12 * (omega^3 scale 1e3): 1e-6 relative
      EXPECT_NEAR(eq.holdingForceRate(ys.data()), fd, 1e-6 * (1 + std::abs(fd)))
          << "trial " << trial;
    }
  }
}

// One combined impulse (ticks on every other pendulum, alternating sides, and an impulse on x):
// the velocity jump is M^-1 p with the dense mass matrix, the kinetic energy jump p.(u + du/2),
// and the horizontal momentum changes by exactly the impulse on x.
TEST(DirectEquations, CombinedImpulseMatchesTheDenseMassMatrix) {
  std::mt19937 rng(777);
  std::uniform_real_distribution<double> px_dist(-1e-3, 1e-3);
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 1 + trial % 6;
    RandomCase rc = makeCase(rng, n, Law::Coulomb);
    NetworkEquations eq(rc.rig);
    const Dense d = dense(eq, rc.rig, rc.y);
    std::vector<double> pins(eq.numSwinging(), 0.0);
    Eigen::VectorXd impulse = Eigen::VectorXd::Zero(eq.numSwinging() + 1);
    const double px = trial % 2 ? px_dist(rng) : 0.0;
    impulse(0) = px;
    for (int j = 0; j < eq.numSwinging(); j += 2) {
      const int side = (j / 2) % 2 ? -1 : 1;
      pins[j] = side * eq.pendulum(j).impulse;
      impulse(j + 1) = pins[j];
    }
    const Eigen::VectorXd du = d.M.ldlt().solve(impulse);
    std::vector<double> y = rc.y;
    const double dT = eq.applyImpulse(y.data(), pins.data(), px);
    const double scale = du.cwiseAbs().maxCoeff();
    EXPECT_NEAR(y[kV] - rc.y[kV], du(0), 1e-12 * scale);
    for (int j = 0; j < eq.numSwinging(); ++j)
      EXPECT_NEAR(y[eq.layout().omega(j)] - rc.y[eq.layout().omega(j)], du(j + 1), 1e-12 * scale);
    // positions do not jump
    for (int j = 0; j < eq.numSwinging(); ++j)
      EXPECT_EQ(y[eq.layout().theta(j)], rc.y[eq.layout().theta(j)]);
    EXPECT_NEAR(1.0 / eq.platformMobility(rc.y.data()), 1.0 / d.M.inverse()(0, 0),
                1e-12 * d.M(0, 0));
    // the kinetic energy jump is the energy's (positions fixed: potential unchanged)
    const double dE = eq.energy(y.data()) - eq.energy(rc.y.data());
    EXPECT_NEAR(dT, dE, 1e-10 * (std::abs(dE) + std::abs(eq.energy(rc.y.data()))));
    // the pins' impulses are internal: horizontal momentum M xdot + sum c_j thetadot_j changes
    // by the impulse on x alone
    auto momentum = [&](const std::vector<double>& s) {
      const Dense dd = dense(eq, rc.rig, s);
      Eigen::VectorXd u(eq.numSwinging() + 1);
      u(0) = s[kV];
      for (int j = 0; j < eq.numSwinging(); ++j) u(j + 1) = s[eq.layout().omega(j)];
      return dd.M.row(0).dot(u);
    };
    EXPECT_NEAR(momentum(y) - px, momentum(rc.y), 1e-14 * (1 + std::abs(momentum(rc.y))));
  }
}

// Energy: along any motion (platform moving), dE/dt = -(damping power) - (friction power); the
// rhs's quadrature rates must be exactly the powers the energy loses (tests the ledger's sign and
// the Coulomb power bound * |xdot| while slipping the way xdot points).
TEST(DirectEquations, EnergyRateIsMinusTheDissipatedPower) {
  std::mt19937 rng(99);
  for (int trial = 0; trial < 100; ++trial) {
    const Law law = static_cast<Law>(trial % 3);
    RandomCase rc = makeCase(rng, 1 + trial % 5, law);
    NetworkEquations eq(rc.rig);
    const PlatformMode mode =
        rc.y[kV] > 0 ? PlatformMode::SlipPositive : PlatformMode::SlipNegative;
    std::vector<double> dy(rc.y.size());
    eq.rhs(rc.y.data(), mode, dy.data());
    const double h = 1e-7;
    std::vector<double> yp = rc.y, ym = rc.y;
    for (size_t k = 0; k < yp.size(); ++k) {
      yp[k] += h * dy[k];
      ym[k] -= h * dy[k];
    }
    const double dE = (eq.energy(yp.data()) - eq.energy(ym.data())) / (2 * h);
    const double loss = dy[eq.layout().dampingWork()] + dy[eq.layout().frictionWork()];
    EXPECT_GE(dy[eq.layout().frictionWork()], 0.0);
    // central difference of a smooth function: O(h^2) + rounding of E (1e-16 * |E| / h)
    EXPECT_NEAR(dE, -loss, 1e-6 * (1 + std::abs(loss))) << "trial " << trial;
  }
}

}  // namespace
}  // namespace metrosync::network
