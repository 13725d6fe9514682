#include "tools/bench/peer_scene.h"

#include <cstdio>
#include <stdexcept>

#include "base/number_text.h"

namespace metrosync::bench {

namespace {

std::string exactList(const std::vector<double>& v) {
  std::string s;
  for (double x : v) s += (s.empty() ? "" : ",") + numberText(x, 17);
  return s;
}

// What the peer lacks of the law (it has Coulomb's law, or none on a moving platform), asked of
// the law's traits, never its name: "" when it has everything.
std::string peerLacksLaw(const FrictionLaw& law) {
  const std::string named = " ({law: " + std::string(law.name()) + "})";
  if (!law.platformMoves()) return "a fixed platform" + named + ": the peer's platform moves";
  if (!law.exertsForce() || law.coulombCoefficient()) return "";
  if (!law.setValued())
    return "a smooth friction force" + named +
           ", e.g. viscous: the peer has Coulomb friction or none";
  const SetValuedLaw bounds = law.platform(1.0).bounds();
  if (bounds.staticBound() != bounds.kineticBound())
    return "static friction above kinetic" + named + ": the peer has Coulomb's law";
  return "a slip force that changes with the speed" + named + ": the peer has Coulomb's law";
}

}  // namespace

std::string peerUnsupported(const Scene& scene) {
  const Rig& rig = scene.rig;
  const int n = static_cast<int>(rig.metronomes.size());
  if (n < 1) return "no metronome";
  if (n > kPeerMaxMetronomes)
    return "N = " + std::to_string(n) + ": the peer is compiled for 1.." +
           std::to_string(kPeerMaxMetronomes) + " metronomes";
  for (const MetronomeSpec& m : rig.metronomes)
    if (m.locked) return "metronome " + m.name + " is locked: the peer has no locked pendulum";
  if (const std::string why = peerLacksLaw(rig.platform.friction); !why.empty()) return why;
  if (rig.platform.spring_N_m != 0) return "a platform spring: the peer has none";
  return "";
}

std::vector<std::string> peerSceneArguments(const Scene& scene) {
  if (const std::string why = peerUnsupported(scene); !why.empty())
    throw std::invalid_argument("the careful peer cannot run " + scene.name + ": " + why);
  const ScaledParams& sp = scene.scaled;
  std::vector<double> y0 = sp.theta0;
  y0.insert(y0.end(), sp.thetadot0.begin(), sp.thetadot0.end());
  y0.push_back(sp.x0);
  y0.push_back(sp.xdot0);
  // a law without friction (none) is the peer's free platform, mu = 0
  const double mu = sp.friction.coulombCoefficient().value_or(0.0);
  return {"--eps",   numberText(sp.epsilon, 17),
          "--mu",    numberText(mu, 17),
          "--nu",    exactList(sp.nu),
          "--J",     exactList(sp.J),
          "--thc",   exactList(sp.theta_c),
          "--alpha", exactList(sp.alpha),
          "--zeta",  exactList(sp.zeta),
          "--y0",    exactList(y0),
          "--t_end", numberText(scene.rig.sim.t_end_s / sp.time_scale_s, 17)};
}

std::vector<double> benchFinalState(const std::vector<double>& peer_state) {
  if (peer_state.size() < 4 || peer_state.size() % 2 != 0) return {};
  const size_t n = (peer_state.size() - 2) / 2;
  std::vector<double> s = {peer_state[2 * n + 1]};
  for (size_t i = 0; i < n; ++i) {
    s.push_back(peer_state[i]);
    s.push_back(peer_state[n + i]);
  }
  return s;
}

}  // namespace metrosync::bench
