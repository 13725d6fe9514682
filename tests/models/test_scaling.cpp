// Physical <-> scaled parameters (models/scaling.h): the paper's section 3 numbers, the round
// trip through the equivalent physical system, the closed forms A_star / J_estimate, and a
// non-identical pair worked out from the paper's own definitions (s2.1).
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <random>
#include <stdexcept>

#include "base/constants.h"
#include "contact/law_registry.h"
#include "models/scaling.h"

namespace metrosync {
namespace {

// The physical experiment of the paper's section 3 (Wittner metronomes, high-friction rollers).
Rig sectionThreeRig() {
  Rig rig;
  rig.gravity_m_s2 = 9.81;
  rig.platform.mass_kg = 0.1432;
  rig.platform.friction = FrictionLaw::coulomb(4.6e-3);
  for (const char* name : {"A", "B"}) {
    MetronomeSpec mt;
    mt.name = name;
    mt.box_mass_kg = 0.0602;
    mt.pendulum_mass_kg = 0.0226;
    mt.length_m = 0.0225;
    mt.inertia_kgm2 = mt.pendulum_mass_kg * mt.length_m * mt.length_m;
    // decay rate beta = 0.5 1/s: nu-bar = 2 beta I / L^2 = 2 beta m
    mt.damping_kg_s = 2.0 * 0.5 * mt.inertia_kgm2 / (mt.length_m * mt.length_m);
    mt.theta_c_rad = 14.0 * kPi / 180.0;
    rig.metronomes.push_back(mt);
  }
  rig.sim.t_end_s = 100.0;
  return rig;
}

TEST(Scaling, ReproducesThePapersSectionThreeNumbers) {
  const Rig rig = sectionThreeRig();
  EXPECT_NEAR(rig.totalMass(), 0.3088, 1e-12);  // "M = 308.8 g"
  ScaledParams p = computeScaled(rig);

  // Tolerances: half a unit in the last digit the paper prints, so each assertion fails as soon
  // as the value would round differently.
  EXPECT_NEAR(p.epsilon, 0.073, 0.0005);              // "epsilon = m/M = 0.073"
  EXPECT_NEAR(p.theta_c[0], 0.9, 0.05);               // "theta_c = 0.9"
  EXPECT_NEAR(p.nu[0], 0.65, 0.005);                  // "nu = 0.65"
  EXPECT_NEAR(*p.friction.value("mu"), 0.23, 0.005);  // "mu = 0.23"
  const double A_star = 0.785 / std::sqrt(p.epsilon);
  EXPECT_NEAR(A_star, 2.9, 0.05);  // "A_star = 2.9"
  const double J = impulseForAmplitude(p.nu[0], A_star, p.theta_c[0]);
  EXPECT_NEAR(J, 3.14, 0.005);  // "J = 3.14"

  // the paper's own shortcut for I = m L^2: nu = (2 beta / eps) sqrt(L / g); same formula, so
  // only rounding separates them
  EXPECT_NEAR(p.nu[0], 2 * 0.5 / p.epsilon * std::sqrt(0.0225 / 9.81), 1e-13);
  // identical metronomes: alpha = zeta = 0 up to rounding amplified by 1/eps
  EXPECT_NEAR(p.alpha[1], 0.0, 1e-13);
  EXPECT_NEAR(p.zeta[1], 0.0, 1e-13);
}

TEST(Scaling, NonIdenticalPairMatchesThePapersDefinitions) {
  Rig rig;
  rig.gravity_m_s2 = 9.81;
  rig.platform.mass_kg = 0.2;
  rig.platform.friction = FrictionLaw::coulomb(1e-3);
  rig.platform.start_x_m = 1e-3;
  rig.platform.start_v_m_s = -2e-3;
  MetronomeSpec a, b;
  a.box_mass_kg = 0.05, a.pendulum_mass_kg = 0.02, a.length_m = 0.03, a.inertia_kgm2 = 2e-5;
  a.damping_kg_s = 0.01, a.impulse_Nms = 1e-5, a.theta_c_rad = 0.25;
  a.start_angle_rad = 0.4, a.start_rate_rad_s = -1.0;
  b.box_mass_kg = 0.06, b.pendulum_mass_kg = 0.025, b.length_m = 0.028, b.inertia_kgm2 = 2.2e-5;
  b.damping_kg_s = 0.012, b.impulse_Nms = 1.2e-5, b.theta_c_rad = 0.3;
  b.start_angle_rad = -0.2, b.start_rate_rad_s = 3.0;
  rig.metronomes = {a, b};
  rig.sim.t_end_s = 50.0;
  const ScaledParams p = computeScaled(rig);

  // by hand: M = 0.2 + 0.07 + 0.085 = 0.355 kg, eps = (0.02 * 0.03)^2 / (2e-5 * 0.355)
  //   = 3.6e-7 / 7.1e-6 = 0.0507042253521127
  const double M = 0.355, g = 9.81;
  EXPECT_NEAR(p.epsilon, 0.0507042253521127, 1e-15);
  const double eps = p.epsilon, se = std::sqrt(eps);
  const double m1 = 0.02, L1 = 0.03, I1 = 2e-5, m2 = 0.025, L2 = 0.028, I2 = 2.2e-5;
  const double root = std::sqrt(m1 * L1 * g * I1);

  // s2.1, written exactly as the paper does (metronome 2 through alpha, sigma, gamma, zeta);
  // the code uses the per-metronome forms of models/scaling.h, so agreement is to rounding
  // (relative 1e-13: a few operations on ~1e-16, divided by eps ~ 0.05 in alpha and zeta)
  const double nu = 0.01 * L1 * L1 / (eps * root);
  const double J = 1e-5 / (eps * std::sqrt(m1 * g * L1 * I1 * eps));
  const double alpha = (I1 * L2 * m2 / (I2 * L1 * m1) - 1) / eps;
  const double sigma = (I1 * L2 * L2 * 0.012 / (I2 * L1 * L1 * 0.01) - 1) / eps;
  const double gamma = (I1 * 1.2e-5 / (I2 * 1e-5) - 1) / eps;
  const double zeta = (m2 * L2 / (m1 * L1) - 1) / eps;
  EXPECT_NEAR(p.nu[0], nu, 1e-13 * nu);
  EXPECT_NEAR(p.J[0], J, 1e-13 * J);
  EXPECT_NEAR(p.nu[1], (1 + eps * sigma) * nu, 1e-13 * nu);  // e2.1b: eps (1 + eps sigma) nu
  EXPECT_NEAR(p.J[1], (1 + eps * gamma) * J, 1e-13 * J);     // e2.1b: eps (1 + eps gamma) J
  EXPECT_NEAR(p.alpha[1], alpha, 1e-12);
  EXPECT_NEAR(p.zeta[1], zeta, 1e-12);
  EXPECT_GT(std::abs(p.alpha[1]), 0.5);  // the pair really is non-identical
  EXPECT_GT(std::abs(p.zeta[1]), 0.5);
  EXPECT_EQ(p.alpha[0], 0.0);  // metronome 1 is the reference
  EXPECT_EQ(p.zeta[0], 0.0);
  EXPECT_NEAR(p.theta_c[0], 0.25 / se, 1e-14);
  EXPECT_NEAR(p.theta_c[1], 0.3 / se, 1e-14);
  EXPECT_NEAR(*p.friction.value("mu"), 1e-3 / (eps * se), 1e-15);

  // unit conversions and starts: t = t-bar omega0, theta = theta-bar / sqrt(eps),
  // x = m1 L1 x-bar / (I1 eps^{3/2})
  const double omega0 = std::sqrt(m1 * L1 * g / I1);
  EXPECT_NEAR(p.time_scale_s, 1 / omega0, 1e-15);
  EXPECT_NEAR(p.angle_scale, se, 1e-15);
  EXPECT_NEAR(p.x_scale_m, I1 * eps * se / (m1 * L1), 1e-17);
  EXPECT_NEAR(p.theta0[0], 0.4 / se, 1e-13);
  EXPECT_NEAR(p.thetadot0[0], -1.0 / (se * omega0), 1e-13);
  EXPECT_NEAR(p.theta0[1], -0.2 / se, 1e-13);
  EXPECT_NEAR(p.thetadot0[1], 3.0 / (se * omega0), 1e-13);
  EXPECT_NEAR(p.x0, m1 * L1 * 1e-3 / (I1 * eps * se), 1e-12);
  EXPECT_NEAR(p.xdot0, m1 * L1 * -2e-3 / (I1 * eps * se) / omega0, 1e-12);
  EXPECT_NEAR(p.tau_end, eps * omega0 * 50.0, 1e-12);

  // viscous: c = c-bar / (M omega0); the law has no mu
  rig.platform.friction = FrictionLaw::viscous(0.05);
  const ScaledParams v = computeScaled(rig);
  EXPECT_NEAR(*v.friction.value("c"), 0.05 / (M * omega0), 1e-15);
  EXPECT_FALSE(v.friction.value("mu"));
  // static friction above kinetic: both coefficients scale as mu = mu-bar / eps^{3/2}
  rig.platform.friction = FrictionLaw(staticCoulombLaw(), {1e-3, 2e-3});
  const ScaledParams s = computeScaled(rig);
  EXPECT_NEAR(*s.friction.value("mu"), 1e-3 / (eps * se), 1e-15);
  EXPECT_NEAR(*s.friction.value("mu_static"), 2e-3 / (eps * se), 1e-15);
}

// Random scaled inputs -> equivalent physical system -> scaled again.
TEST(Scaling, RoundTripThroughTheEquivalentSystem) {
  std::mt19937_64 rng(20240611);
  auto uni = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  for (int trial = 0; trial < 500; ++trial) {
    ScaledRigInput in;
    const int n = 1 + trial % 5;
    // with |alpha|, |zeta| <= 2, eps <= 0.6 / (1.69 n) keeps eps * sum_i (1 + eps zeta_i)
    // (1 + eps alpha_i) below 0.51: every draw has an equivalent system with a platform
    in.epsilon = uni(0.01, 0.6 / (n * 1.69));
    const double mu = uni(0, 3), c = uni(0, 3);
    const FrictionLaw laws[] = {FrictionLaw::coulomb(mu), FrictionLaw::viscous(c),
                                FrictionLaw::none(), FrictionLaw::fixed(),
                                FrictionLaw(staticCoulombLaw(), {mu, mu + c})};
    in.friction = laws[trial % 5];
    in.x0 = uni(-2, 2);
    in.xdot0 = uni(-2, 2);
    in.tau_end = uni(1, 1000);
    in.accuracy = uni(1e-12, 1e-4);
    in.sample = uni(0.01, 1);
    in.integrator = "rk";
    for (int i = 0; i < n; ++i) {
      ScaledMetronomeInput m;
      m.nu = uni(0, 2);
      m.J = uni(0, 6);
      m.theta_c = uni(0.1, 2);
      m.alpha = i == 0 ? 0.0 : uni(-2, 2);
      m.zeta = i == 0 ? 0.0 : uni(-2, 2);
      m.theta0 = uni(-3, 3);
      m.thetadot0 = uni(-3, 3);
      in.metronomes.push_back(m);
    }
    const Rig rig = rigFromScaled(in);
    ASSERT_GT(rig.platform.mass_kg, 0.0);
    EXPECT_EQ(rig.units, Units::Scaled);
    const ScaledParams p = computeScaled(rig);

    // Values O(1) pass through a handful of products and quotients: a few ulp, 1e-14 relative
    // with an absolute floor of 1e-14. alpha and zeta are recovered as (ratio - 1) / eps with the
    // ratio good to a few ulp, so their error is a few ulp / eps: allow 16 ulp / eps.
    auto close = [](double a, double b) {
      return std::abs(a - b) <= 1e-14 * std::max(1.0, std::abs(b));
    };
    const double detune_tol = 16 * DBL_EPSILON / in.epsilon;
    EXPECT_TRUE(close(p.epsilon, in.epsilon)) << p.epsilon << " vs " << in.epsilon;
    EXPECT_TRUE(p.friction.is(in.friction.kind()));
    for (std::size_t k = 0; k < in.friction.values().size(); ++k)
      EXPECT_TRUE(close(p.friction.values()[k], in.friction.values()[k]))
          << p.friction.name() << " " << k;
    EXPECT_TRUE(close(p.x0, in.x0));
    EXPECT_TRUE(close(p.xdot0, in.xdot0));
    EXPECT_TRUE(close(p.tau_end, in.tau_end)) << p.tau_end << " vs " << in.tau_end;
    EXPECT_TRUE(close(p.time_scale_s, 1.0));
    EXPECT_EQ(rig.sim.accuracy, in.accuracy);
    EXPECT_EQ(rig.sim.integrator, in.integrator);
    EXPECT_TRUE(close(rig.sim.sample_s / p.time_scale_s, in.sample));
    ASSERT_EQ(p.nu.size(), in.metronomes.size());
    for (int i = 0; i < n; ++i) {
      const ScaledMetronomeInput& m = in.metronomes[i];
      EXPECT_TRUE(close(p.nu[i], m.nu)) << i << ": " << p.nu[i] << " vs " << m.nu;
      EXPECT_TRUE(close(p.J[i], m.J)) << i << ": " << p.J[i] << " vs " << m.J;
      EXPECT_TRUE(close(p.theta_c[i], m.theta_c));
      EXPECT_NEAR(p.alpha[i], m.alpha, detune_tol);
      EXPECT_NEAR(p.zeta[i], m.zeta, detune_tol);
      EXPECT_TRUE(close(p.theta0[i], m.theta0));
      EXPECT_TRUE(close(p.thetadot0[i], m.thetadot0));
    }
  }
}

TEST(Scaling, EquivalentSystemIsThePapersNormalisation) {
  ScaledRigInput in;
  in.epsilon = 0.1;
  in.metronomes.resize(2);
  in.metronomes[1].alpha = 0.5;
  in.metronomes[1].zeta = -1.0;
  const Rig rig = rigFromScaled(in);
  // m1 = L1 = g = I1 = 1, M = 1/eps; metronome 2: L = 1/(1 + eps alpha), m = (1+eps zeta)(1+eps
  // alpha); exact in binary floating point up to one rounding each
  EXPECT_EQ(rig.gravity_m_s2, 1.0);
  EXPECT_EQ(rig.metronomes[0].pendulum_mass_kg, 1.0);
  EXPECT_EQ(rig.metronomes[0].length_m, 1.0);
  EXPECT_EQ(rig.metronomes[0].inertia_kgm2, 1.0);
  EXPECT_NEAR(rig.totalMass(), 10.0, 1e-14);
  EXPECT_NEAR(rig.metronomes[1].length_m, 1 / 1.05, 1e-15);
  EXPECT_NEAR(rig.metronomes[1].pendulum_mass_kg, 0.9 * 1.05, 1e-15);
  EXPECT_NEAR(rig.metronomes[1].inertia_kgm2, 0.9 * 1.05 / (1.05 * 1.05), 1e-15);
  EXPECT_EQ(rig.metronomes[1].box_mass_kg, 0.0);
  EXPECT_NEAR(rig.platform.mass_kg, 10.0 - 1.0 - 0.945, 1e-14);
}

TEST(Scaling, EpsilonTooLargeForTheMetronomesIsRefused) {
  ScaledRigInput in;
  in.epsilon = 0.3;  // 4 point pendulums of mass 1 against M = 1/0.3 = 3.33
  in.metronomes.resize(4);
  try {
    rigFromScaled(in);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("too large for 4 metronomes"), std::string::npos)
        << e.what();
  }
  in.metronomes.resize(3);  // 3 < 3.33: a light platform remains
  EXPECT_NEAR(rigFromScaled(in).platform.mass_kg, 1 / 0.3 - 3, 1e-14);

  in.metronomes[0].alpha = 0.1;  // metronome 1 is the reference
  EXPECT_THROW(rigFromScaled(in), std::invalid_argument);
}

TEST(Scaling, SteadyAmplitudeAndImpulseAreInverse) {
  std::mt19937_64 rng(7);
  auto uni = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  for (int k = 0; k < 1000; ++k) {
    const double nu = uni(0.05, 3), theta_c = uni(0.05, 3);
    // any stable amplitude: A >= sqrt(2) theta_c
    const double A = theta_c * uni(std::sqrt(2.0), 10.0);
    const double J = impulseForAmplitude(nu, A, theta_c);
    EXPECT_GE(J, criticalImpulse(nu, theta_c) * (1 - 1e-14));
    const std::optional<double> back = steadyAmplitude(nu, J, theta_c);
    ASSERT_TRUE(back.has_value());
    // near A = sqrt(2) theta_c (J -> J_c) the inner square root loses digits: sqrt(1 - r^2)
    // with 1 - r^2 ~ (A^2 - 2 theta_c^2)^2 / A^4; 1e-7 relative covers draws within 1e-8 of it
    EXPECT_NEAR(*back, A, 1e-7 * A) << "nu " << nu << " theta_c " << theta_c;
    // and R(A) = -nu A / 2 + J / pi sqrt(1 - theta_c^2 / A^2) = 0 there (e5.1)
    EXPECT_NEAR(-nu * A / 2 + J / kPi * std::sqrt(1 - theta_c * theta_c / (A * A)), 0.0,
                1e-12 * nu * A);
  }
  // well inside the stable branch the inverse is exact to rounding
  EXPECT_NEAR(*steadyAmplitude(0.65, impulseForAmplitude(0.65, 2.9, 0.9), 0.9), 2.9, 1e-14);
}

TEST(Scaling, SteadyAmplitudeThreshold) {
  // J_c = pi nu theta_c; at J = J_c the saddle-node sits at A = sqrt(2) theta_c
  EXPECT_DOUBLE_EQ(criticalImpulse(1.0, 1.0), kPi);
  const std::optional<double> at_jc = steadyAmplitude(1.0, kPi, 1.0);
  ASSERT_TRUE(at_jc.has_value());
  EXPECT_NEAR(*at_jc, std::sqrt(2.0), 1e-15);
  EXPECT_FALSE(steadyAmplitude(1.0, 3.0, 1.0).has_value());  // fig. f7(b): J = 3 < pi
  EXPECT_TRUE(steadyAmplitude(1.0, 4.0, 1.0).has_value());   // fig. f7(a): J = 4 > pi
  EXPECT_FALSE(steadyAmplitude(1.0, 0.0, 1.0).has_value());  // no escapement
  EXPECT_FALSE(steadyAmplitude(0.0, 1.0, 1.0).has_value());  // no damping: grows forever
  // fig. f7(a): nu = theta_c = 1, J = 4: A = (4/pi) sqrt(2 (1 + sqrt(1 - pi^2/16)))
  EXPECT_NEAR(*steadyAmplitude(1.0, 4.0, 1.0),
              4 / kPi * std::sqrt(2 * (1 + std::sqrt(1 - kPi * kPi / 16))), 1e-15);

  EXPECT_THROW(impulseForAmplitude(1.0, 1.3, 1.0), std::invalid_argument);  // < sqrt(2) theta_c
  EXPECT_THROW(impulseForAmplitude(0.0, 3.0, 1.0), std::invalid_argument);  // nu = 0
  EXPECT_NEAR(impulseForAmplitude(1.0, std::sqrt(2.0), 1.0), kPi, 1e-14);   // J_c
}

}  // namespace
}  // namespace metrosync
