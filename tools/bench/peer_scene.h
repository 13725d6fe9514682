// A bench scene as the careful peer's command line (../shared/peer/README.md), and the peer's
// answer as the bench's final state. The peer integrates the paper's scaled equations e2.1a-c;
// a rig (physical or scaled) is the same system in the scaled variables of models/scaling.h
// (computeScaled: epsilon, mu, and per metronome nu, J, theta_c, alpha, zeta; the peer's sigma
// and gamma are 0, metrosync's nu_i and J_i already hold each metronome's own damping and kick).
// What the peer lacks (more than 8 metronomes, a locked pendulum, a platform spring, viscous
// friction, a fixed platform) makes a scene unsupported, with the reason.
#pragma once

#include <string>
#include <vector>

#include "tools/bench/bench_scene.h"

namespace metrosync::bench {

// The peer is compiled for N = 1 .. 8 metronomes.
constexpr int kPeerMaxMetronomes = 8;

// Why the peer cannot run `scene` ("" when it can).
std::string peerUnsupported(const Scene& scene);

// The scene's arguments for the peer (the scaled parameters, --y0 with the start in scaled
// units, --t_end), without the binary and the method's own flags. Numbers are written with 17
// significant digits: they read back bit for bit. Throws std::invalid_argument (the reason) for
// an unsupported scene.
std::vector<std::string> peerSceneArguments(const Scene& scene);

// The peer's final state (th_1..th_N, th'_1..th'_N, x, x') as the bench's scaled final state
// (xdot, theta_1, thetadot_1, ..., theta_N, thetadot_N; see bench_run.h). Empty when the state
// is not 2N + 2 values.
std::vector<double> benchFinalState(const std::vector<double>& peer_state);

}  // namespace metrosync::bench
