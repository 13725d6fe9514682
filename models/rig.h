// The immutable description of a rig: one platform, N >= 1 metronomes, and how to simulate it.
// Always held in SI units (radians); a scaled rig is stored as an equivalent physical system
// (m1 = L1 = g = 1, I1 = m1 L1^2, M = m1 / epsilon; see models/scaling.h) with `units` telling
// the outputs to report in scaled variables.
#pragma once

#include <string>
#include <vector>

#include "contact/friction_law.h"

namespace metrosync {

enum class Units { Physical, Scaled };

const char* toString(Units u);

struct MetronomeSpec {
  std::string name;
  double box_mass_kg = 0.0;       // the metronome without its pendulum
  double pendulum_mass_kg = 0.0;  // m_i
  double length_m = 0.0;          // L_i, pivot to centre of mass
  double inertia_kgm2 = 0.0;      // I_i about the pivot (>= m_i L_i^2)
  double damping_kg_s = 0.0;      // nu-bar_i: pivot torque -nu-bar_i L_i^2 thetadot (e1.1a)
  double air_drag_Nms2 = 0.0;  // d_i: air drag, pivot torque -d_i thetadot |thetadot| (full model)
  double theta_c_rad = 0.0;    // critical angle of the escapement (both sides)
  double impulse_Nms = 0.0;    // J-bar_i, angular impulse per tick; 0 = no escapement
  bool locked = false;         // pendulum held in its box (paper section 3A): no pin at all
  double start_angle_rad = 0.0;   // theta-bar_i(0)
  double start_rate_rad_s = 0.0;  // theta-bar_i'(0)
};

struct PlatformSpec {
  double mass_kg = 0.0;      // the board alone (boxes and pendulums are added for M_total)
  FrictionLaw friction;      // physical units: mu-bar (|F| = mu-bar M_total g), c-bar in N s/m
  double spring_N_m = 0.0;   // optional spring to ground (section 3A); 0 = none
  double start_x_m = 0.0;    // x-bar(0)
  double start_v_m_s = 0.0;  // x-bar'(0)
};

struct SimulationSettings {
  double t_end_s = 0.0;    // physical duration
  double accuracy = 1e-8;  // relative local error target of the integrator
  std::string integrator;  // empty = the default integrator
  double sample_s = 0.0;   // trajectory output interval; 0 = default (>= 20 per period)
};

struct Rig {
  std::string name = "rig";
  Units units = Units::Physical;  // as the user wrote it: decides the units of trajectory.csv
  double gravity_m_s2 = 9.81;
  PlatformSpec platform;
  std::vector<MetronomeSpec> metronomes;
  SimulationSettings sim;

  // M in the paper: the platform plus every metronome (boxes and pendulums).
  double totalMass() const;
  // Number of metronomes whose pendulum swings (not locked).
  int numSwinging() const;
  // What only the full model's engines take, as the key that sets it
  // ("metronomes.0.pendulum.air_drag"), or "" when nothing: the slow flow and the derivatives of
  // `continue --model full` and `fit` refuse a rig with it.
  std::string fullModelOnlyKey() const;
};

}  // namespace metrosync
