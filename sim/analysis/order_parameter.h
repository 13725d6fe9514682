// Kuramoto's order parameter of a group of metronomes (docs/networks.md):
//   r exp(i Phi) = (1/n) sum_j exp(i phi_j),
// r = 1 when every phase is the same, r ~ 1/sqrt(n) for independent uniform phases (the mean of
// n unit vectors: E r^2 = 1/n), Phi the group's mean phase. A metronome's phase comes from its
// state as in the envelope (s2.1: theta = A sin phi, thetadot = A omega cos phi), with its own
// small-angle frequency omega = sqrt(m g L / I).
#pragma once

#include <vector>

namespace metrosync {

struct Order {
  double r = 0.0;    // in [0, 1]
  double Phi = 0.0;  // mean phase in (-pi, pi]; 0 when r == 0
};

// Phase of a pendulum at angle theta (rad), rate thetadot (rad/s), frequency omega (rad/s).
double pendulumPhase(double theta, double thetadot, double omega);

// The order parameter of the given phases (rad); r = 0 for none.
Order orderParameter(const std::vector<double>& phases);

}  // namespace metrosync
