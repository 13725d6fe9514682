#include "models/network.h"

#include <algorithm>
#include <stdexcept>

namespace metrosync {

int Network::numMetronomes() const {
  int n = 0;
  for (const NetworkPlatform& p : platforms) n += static_cast<int>(p.rig.metronomes.size());
  return n;
}

double Network::carriedMass(int p) const {
  double m = platforms[p].rig.totalMass();
  for (int q = 0; q < static_cast<int>(platforms.size()); ++q)
    if (platforms[q].on == p) m += carriedMass(q);
  return m;
}

int Network::firstMetronome(int p) const {
  int n = 0;
  for (int q = 0; q < p; ++q) n += static_cast<int>(platforms[q].rig.metronomes.size());
  return n;
}

Network networkOfOne(const Rig& rig) {
  Network net;
  net.name = rig.name;
  net.gravity_m_s2 = rig.gravity_m_s2;
  net.sim = rig.sim;
  NetworkPlatform p;
  p.name = "platform";
  p.rig = rig;
  net.platforms.push_back(p);
  return net;
}

bool Network::isSingleRig() const {
  return platforms.size() == 1 && couplings.empty() && platforms[0].on < 0 &&
         platforms[0].spring_c_Ns_m == 0.0;
}

Rig Network::toSingleRig() const {
  Rig rig = platforms.at(0).rig;
  rig.name = name;
  return rig;
}

Rig Network::unionRig() const {
  Rig rig = platforms.at(0).rig;
  rig.metronomes.clear();
  for (const NetworkPlatform& p : platforms)
    for (const MetronomeSpec& m : p.rig.metronomes)
      if (!m.locked) rig.metronomes.push_back(m);
  if (rig.metronomes.empty()) throw std::invalid_argument("the network has no swinging pendulum");
  if (!rig.platform.friction.platformMoves()) rig.platform.friction = FrictionLaw::none();
  rig.platform.mass_kg = std::max(rig.platform.mass_kg, 1.0);  // scales only
  return rig;
}

Rig Network::scalesRig() const {
  Rig rig = platforms.at(0).rig;
  rig.metronomes.clear();
  for (const NetworkPlatform& p : platforms)
    for (const MetronomeSpec& m : p.rig.metronomes)
      if (!m.locked && rig.metronomes.empty()) rig.metronomes.push_back(m);
  if (!rig.platform.friction.platformMoves()) rig.platform.friction = FrictionLaw::none();
  return rig;
}

}  // namespace metrosync
