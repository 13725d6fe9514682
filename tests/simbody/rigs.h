// Small rigs built in code for the engine's tests (no YAML: the loader has its own tests).
#pragma once

#include <cmath>

#include "models/rig.h"
#include "models/scaling.h"

namespace metrosync::testrigs {

// The paper's experiment (section 3): two Wittner metronomes, m = 22.6 g, L = 2.25 cm, I = m L^2,
// platform 143.2 g, boxes 60.2 g, theta_c = 14 deg, decay rate 0.5 1/s, steady amplitude 45 deg.
inline Rig experiment(double mu_bar, double duration_s) {
  Rig rig;
  rig.name = "experiment";
  rig.units = Units::Physical;
  rig.platform.mass_kg = 0.1432;
  rig.platform.friction = FrictionLaw::coulomb(mu_bar);
  for (int i = 0; i < 2; ++i) {
    MetronomeSpec m;
    m.box_mass_kg = 0.0602;
    m.pendulum_mass_kg = 0.0226;
    m.length_m = 0.0225;
    m.inertia_kgm2 = m.pendulum_mass_kg * m.length_m * m.length_m;
    m.damping_kg_s = 2 * 0.5 * m.inertia_kgm2 / (m.length_m * m.length_m);
    m.theta_c_rad = 0.244;
    m.impulse_Nms = 1.49e-5;
    m.start_angle_rad = i == 0 ? 0.785 : -0.785;
    m.start_rate_rad_s = i == 0 ? 0.0 : 0.25;
    rig.metronomes.push_back(m);
  }
  rig.sim.t_end_s = duration_s;
  return rig;
}

// A scaled rig with identical metronomes (the paper's section 4 parameters by default).
inline ScaledRigInput scaledPair(double eps, FrictionLaw law, double tau_end, double psi0,
                                 double A0 = 1.9) {
  ScaledRigInput in;
  in.name = "pair";
  in.epsilon = eps;
  in.friction = law;
  in.tau_end = tau_end;
  for (int i = 0; i < 2; ++i) {
    ScaledMetronomeInput m;
    m.nu = 0.7;
    m.J = 2.8;
    m.theta_c = 0.9;
    const double phi = i == 0 ? psi0 : 0.0;
    m.theta0 = A0 * std::sin(phi);
    m.thetadot0 = A0 * std::cos(phi);
    in.metronomes.push_back(m);
  }
  return in;
}

}  // namespace metrosync::testrigs
