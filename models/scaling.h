// Physical <-> scaled parameters, per the paper's section "Dimensionless variables and
// parameters" (s2.1), metronome 1 being the reference:
//   t = t-bar * omega0, omega0 = sqrt(m1 L1 g / I1);  epsilon = m1^2 L1^2 / (I1 M)
//   theta = theta-bar / sqrt(eps);  x = m1 L1 x-bar / (I1 eps^{3/2});  mu = mu-bar / eps^{3/2}
//   per metronome i (generalising e2.1b):
//     1 + eps alpha_i = I1 L_i m_i / (I_i L1 m1)        (frequency detuning)
//     1 + eps zeta_i  = m_i L_i / (m1 L1)               (platform coupling)
//     eps nu_i        = nu-bar_i L_i^2 / (I_i omega0)    (so that e2.1b reads -eps nu_i thetadot_i)
//     eps J_i         = J-bar_i / (I_i sqrt(eps) omega0) (jump of thetadot_i on a still platform)
//     theta_c,i       = theta-bar_c,i / sqrt(eps)
//   viscous platform: c = c-bar / (M omega0)  (scaled platform equation xddot = -c xdot - ...)
//   (each law parameter scales by its unit, LawUnit in contact/law_kind.h: lawScales below)
#pragma once

#include <optional>
#include <vector>

#include "models/rig.h"

namespace metrosync {

struct ScaledParams {
  double epsilon = 0.0;
  FrictionLaw friction;  // the platform's law in scaled units (mu = mu-bar / eps^{3/2}, ...)
  // per metronome, (N x 1)
  std::vector<double> nu, J, theta_c, alpha, zeta;
  std::vector<std::optional<double>> A_star;  // eq. A_star; empty where J < J_c
  std::vector<bool> locked;
  // start in scaled variables
  std::vector<double> theta0, thetadot0;
  double x0 = 0.0, xdot0 = 0.0;
  // unit conversions: physical = scale * scaled
  double time_scale_s = 1.0;  // seconds per unit of scaled time, 1/omega0
  double angle_scale = 1.0;   // sqrt(eps)
  double x_scale_m = 1.0;     // I1 eps^{3/2} / (m1 L1)
  double tau_end = 0.0;       // slow time at the end of the run
};

// The scales a law parameter's unit is made of (contact/friction_law.h): eps^{3/2} for a
// friction coefficient, the mass M, the length x_scale and the rate omega0 (a viscous c by
// M omega0, a velocity by x_scale omega0).
LawScales lawScales(double epsilon, double M, double x_scale, double omega0);

// Scaled parameters of a rig (physical or an equivalent system built from scaled input).
ScaledParams computeScaled(const Rig& rig);

// The input of a `units: scaled` rig, before it becomes an equivalent physical system.
struct ScaledMetronomeInput {
  std::string name;
  double nu = 0.0, J = 0.0, theta_c = 0.0, alpha = 0.0, zeta = 0.0;
  double theta0 = 0.0, thetadot0 = 0.0;  // scaled start ({A, phi}: theta = A sin phi, ...)
};
struct ScaledRigInput {
  std::string name = "rig";
  double epsilon = 0.0;
  FrictionLaw friction;  // in scaled units
  std::vector<ScaledMetronomeInput> metronomes;
  double x0 = 0.0, xdot0 = 0.0;
  double tau_end = 0.0;
  double accuracy = 1e-8;
  std::string integrator;
  double sample = 0.0;  // in scaled time t; 0 = default
};

// The equivalent physical system: m1 = L1 = g = 1, I1 = 1, M = 1/eps; metronome i a point
// pendulum with L_i = 1/(1 + eps alpha_i), m_i = (1 + eps zeta_i)(1 + eps alpha_i).
// Throws std::invalid_argument when no such system exists (platform mass <= 0, i.e. the mass
// matrix would not be positive definite: eps * sum_i (1+eps zeta_i)(1+eps alpha_i) >= 1).
Rig rigFromScaled(const ScaledRigInput& in);

// eq. A_star: steady amplitude of one metronome on a still platform; nullopt if J < J_c, and also
// if J = 0 (no escapement) or nu = 0 (no damping: the amplitude grows without bound).
std::optional<double> steadyAmplitude(double nu, double J, double theta_c);
// J_c = pi nu theta_c: below it the metronome stops.
double criticalImpulse(double nu, double theta_c);
// eq. J_estimate: the impulse that gives steady amplitude A_star. A_star is the stable root of
// e5.1 only when A_star >= sqrt(2) theta_c (below it, it is the unstable one), so that is
// required, with nu > 0; throws std::invalid_argument otherwise. Inverse of steadyAmplitude.
double impulseForAmplitude(double nu, double A_star, double theta_c);

}  // namespace metrosync
