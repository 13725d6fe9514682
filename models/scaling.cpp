// Physical <-> scaled parameters (paper s2.1, generalised to N metronomes; see models/scaling.h)
// and the single-metronome closed forms eq. A_star, J_c and eq. J_estimate.
#include "models/scaling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "base/constants.h"

namespace metrosync {

LawScales lawScales(double epsilon, double M, double x_scale, double omega0) {
  return LawScales{epsilon * std::sqrt(epsilon), M, x_scale, omega0};
}

ScaledParams computeScaled(const Rig& rig) {
  if (rig.metronomes.empty())
    throw std::invalid_argument("computeScaled: the rig has no metronome");
  const MetronomeSpec& ref = rig.metronomes.front();
  const double m1 = ref.pendulum_mass_kg, L1 = ref.length_m, I1 = ref.inertia_kgm2;
  const double g = rig.gravity_m_s2, M = rig.totalMass();
  if (!(m1 > 0 && L1 > 0 && I1 > 0 && g > 0 && M > 0))
    throw std::invalid_argument(
        "computeScaled: metronome 1's pendulum mass, length and inertia, gravity and the total "
        "mass must all be > 0");

  ScaledParams p;
  // s2.1: t = t-bar omega0, eps = m1^2 L1^2 / (I1 M)
  const double omega0 = std::sqrt(m1 * L1 * g / I1);
  const double eps = m1 * m1 * L1 * L1 / (I1 * M);
  const double sqrt_eps = std::sqrt(eps);
  p.epsilon = eps;
  p.time_scale_s = 1.0 / omega0;
  p.angle_scale = sqrt_eps;
  p.x_scale_m = I1 * eps * sqrt_eps / (m1 * L1);
  p.tau_end = eps * omega0 * rig.sim.t_end_s;

  // platform: each law parameter by its unit (mu = mu-bar / eps^{3/2}, c = c-bar / (M omega0),
  // a velocity / (x_scale omega0))
  p.friction = rig.platform.friction.scaled(lawScales(eps, M, p.x_scale_m, omega0));
  p.x0 = rig.platform.start_x_m / p.x_scale_m;
  p.xdot0 = rig.platform.start_v_m_s / (p.x_scale_m * omega0);

  // per metronome (e2.1b generalised): (N x 1) each
  for (const MetronomeSpec& mt : rig.metronomes) {
    const double mL = mt.pendulum_mass_kg * mt.length_m;
    const double alpha = (I1 * mL / (mt.inertia_kgm2 * m1 * L1) - 1.0) / eps;
    const double zeta = (mL / (m1 * L1) - 1.0) / eps;
    const double nu =
        mt.damping_kg_s * mt.length_m * mt.length_m / (mt.inertia_kgm2 * omega0) / eps;
    const double J = mt.impulse_Nms / (mt.inertia_kgm2 * sqrt_eps * omega0) / eps;
    const double theta_c = mt.theta_c_rad / sqrt_eps;
    p.nu.push_back(nu);
    p.J.push_back(J);
    p.theta_c.push_back(theta_c);
    p.alpha.push_back(alpha);
    p.zeta.push_back(zeta);
    p.A_star.push_back(steadyAmplitude(nu, J, theta_c));
    p.locked.push_back(mt.locked);
    p.theta0.push_back(mt.start_angle_rad / sqrt_eps);
    p.thetadot0.push_back(mt.start_rate_rad_s / (sqrt_eps * omega0));
  }
  // metronome 1 is the reference: its alpha and zeta are 0 by definition, not up to rounding
  p.alpha.front() = 0.0;
  p.zeta.front() = 0.0;
  return p;
}

Rig rigFromScaled(const ScaledRigInput& in) {
  const double eps = in.epsilon;
  if (!(eps > 0 && eps < 1))
    throw std::invalid_argument("epsilon must be in (0, 1), got " + std::to_string(eps));
  if (in.metronomes.empty()) throw std::invalid_argument("a rig needs at least one metronome");
  if (in.metronomes.front().alpha != 0.0 || in.metronomes.front().zeta != 0.0)
    throw std::invalid_argument(
        "metronome 1 is the reference: its alpha and zeta are 0 by definition");
  const double sqrt_eps = std::sqrt(eps);
  const double eps32 = eps * sqrt_eps;

  // the equivalent system: m1 = L1 = g = 1, I1 = 1 so that omega0 = 1, M = 1/eps
  Rig rig;
  rig.name = in.name;
  rig.units = Units::Scaled;
  rig.gravity_m_s2 = 1.0;
  const double M = 1.0 / eps;
  double pendulums = 0.0;
  for (std::size_t i = 0; i < in.metronomes.size(); ++i) {
    const ScaledMetronomeInput& s = in.metronomes[i];
    const double detune = 1.0 + eps * s.alpha;  // 1 + eps alpha_i = m_i L_i / I_i
    const double couple = 1.0 + eps * s.zeta;   // 1 + eps zeta_i = m_i L_i
    if (!(detune > 0 && couple > 0))
      throw std::invalid_argument("metronome " + std::to_string(i + 1) +
                                  ": 1 + epsilon alpha and 1 + epsilon zeta must be > 0");
    MetronomeSpec mt;
    mt.name = s.name;
    mt.box_mass_kg = 0.0;
    // point pendulum: I = m L^2, so m L / I = 1/L = 1 + eps alpha and m L = 1 + eps zeta
    mt.length_m = i == 0 ? 1.0 : 1.0 / detune;
    mt.pendulum_mass_kg = i == 0 ? 1.0 : couple * detune;
    mt.inertia_kgm2 = mt.pendulum_mass_kg * mt.length_m * mt.length_m;
    // eps nu_i = nu-bar_i L_i^2 / (I_i omega0)  ->  nu-bar_i = eps nu_i m_i
    mt.damping_kg_s = eps * s.nu * mt.inertia_kgm2 / (mt.length_m * mt.length_m);
    // eps J_i = J-bar_i / (I_i sqrt(eps) omega0)
    mt.impulse_Nms = eps32 * s.J * mt.inertia_kgm2;
    mt.theta_c_rad = sqrt_eps * s.theta_c;
    mt.start_angle_rad = sqrt_eps * s.theta0;
    mt.start_rate_rad_s = sqrt_eps * s.thetadot0;
    pendulums += mt.pendulum_mass_kg;
    rig.metronomes.push_back(mt);
  }
  // the platform carries the rest of M; the mass matrix is positive definite only if it is > 0
  rig.platform.mass_kg = M - pendulums;
  if (!(rig.platform.mass_kg > 0))
    throw std::invalid_argument(
        "epsilon = " + std::to_string(eps) + " is too large for " +
        std::to_string(in.metronomes.size()) +
        " metronomes: the pendulums alone would outweigh M = 1/epsilon (the platform mass would "
        "be <= 0; need epsilon * sum_i (1 + epsilon zeta_i)(1 + epsilon alpha_i) < 1)");

  // omega0 = 1, x_scale = eps^{3/2}: c-bar = c M, a velocity V eps^{3/2}
  rig.platform.friction = in.friction.physical(lawScales(eps, M, eps32, 1.0));
  rig.platform.start_x_m = eps32 * in.x0;  // x_scale = I1 eps^{3/2} / (m1 L1)
  rig.platform.start_v_m_s = eps32 * in.xdot0;

  rig.sim.t_end_s = in.tau_end / eps;  // tau = eps t, and t = t-bar here
  rig.sim.accuracy = in.accuracy;
  rig.sim.integrator = in.integrator;
  rig.sim.sample_s = in.sample;
  return rig;
}

double criticalImpulse(double nu, double theta_c) {
  return kPi * nu * theta_c;
}

std::optional<double> steadyAmplitude(double nu, double J, double theta_c) {
  // no escapement, or no damping (the amplitude then grows without bound): no steady state
  if (!(J > 0) || !(nu > 0)) return std::nullopt;
  if (J < criticalImpulse(nu, theta_c)) return std::nullopt;
  // eq. A_star, the larger (stable) root of R(A) = 0; at J = J_c the root under the inner
  // square root is 0 and rounding must not make it negative
  const double r = criticalImpulse(nu, theta_c) / J;
  const double inner = std::sqrt(std::max(0.0, 1.0 - r * r));
  return J / (kPi * nu) * std::sqrt(2.0 * (1.0 + inner));
}

double impulseForAmplitude(double nu, double A_star, double theta_c) {
  // A_star is the stable fixed point of e5.1 only if A_star >= sqrt(2) theta_c; below it the
  // same J makes A_star the unstable one (and the metronome settles elsewhere)
  if (!(nu > 0)) throw std::invalid_argument("impulseForAmplitude: nu must be > 0");
  if (!(theta_c > 0) || !(A_star * A_star >= 2.0 * theta_c * theta_c))
    throw std::invalid_argument(
        "impulseForAmplitude: a steady amplitude must be >= sqrt(2) theta_c (got A_star = " +
        std::to_string(A_star) + ", theta_c = " + std::to_string(theta_c) + ")");
  // eq. J_estimate
  return kPi / 2.0 * nu * A_star / std::sqrt(1.0 - theta_c * theta_c / (A_star * A_star));
}

}  // namespace metrosync
