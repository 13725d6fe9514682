// A network of platforms (docs/networks.md, issue 13): several boards, each carrying metronomes,
// each on the table or resting on another board, held by optional springs to the ground and
// joined by springs (and dampers) to each other. Physical units (SI, radians).
// Each platform is kept as the single-platform Rig it would be alone (its board, its friction law,
// its ground spring, its start, its metronomes; the network's gravity and simulation settings),
// so that a one-platform network IS today's rig (toSingleRig) and runs today's code path.
#pragma once

#include <string>
#include <vector>

#include "models/rig.h"

namespace metrosync {

struct NetworkPlatform {
  std::string name;
  int on = -1;                 // the platform it rests on (index); -1: on the table
  double spring_c_Ns_m = 0.0;  // damper beside the ground spring rig.platform.spring_N_m
  Rig rig;                     // this platform alone (rig.platform, rig.metronomes)
};

// A spring k (N/m) and damper c (N s/m) between platforms a and b (indices): force on a is
// -k (x_a - x_b) - c (xdot_a - xdot_b), the opposite on b.
struct Coupling {
  int a = 0, b = 0;
  double k_N_m = 0.0;
  double c_Ns_m = 0.0;
};

struct Network {
  std::string name = "network";
  double gravity_m_s2 = 9.81;
  SimulationSettings sim;
  std::vector<NetworkPlatform> platforms;  // in file order
  std::vector<Coupling> couplings;         // in file order

  int numMetronomes() const;
  // The mass platform p carries onto what is below it: its board, its metronomes, and every
  // platform resting on it (recursively), with theirs. The normal force of its friction is
  // carriedMass(p) * g (eq. frictionlaw on each contact).
  double carriedMass(int p) const;
  // Global metronome number (0-based, file order over the whole network) of platform p's first.
  int firstMetronome(int p) const;
  // A network that means exactly one of today's rigs: one platform on the table, no coupling, no
  // ground damper.
  bool isSingleRig() const;
  // That rig (valid when isSingleRig()).
  Rig toSingleRig() const;
  // The rig the engines take their scales (fast period, tolerances) and default integrator from:
  // the first platform's, carrying every swinging metronome of the network (metronome 1 sets the
  // scales). Throws std::invalid_argument when the network has no swinging pendulum.
  Rig unionRig() const;
  // The rig of the network's output scales (tau, scaled A in envelope.csv): the first platform
  // with only the network's first swinging metronome.
  Rig scalesRig() const;
};

// The rig as a network of one platform on the table (the rig's gravity and settings): its
// toSingleRig() is the rig again.
Network networkOfOne(const Rig& rig);

}  // namespace metrosync
