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
  const PlatformFriction f = rig.platform.friction.platform(1.0);
  if (f.kind == PlatformFriction::Kind::Viscous)
    return "viscous friction: the peer has Coulomb friction or none";
  if (f.kind == PlatformFriction::Kind::Fixed) return "a fixed platform: the peer's platform moves";
  if (f.setValued() && f.dry.staticBound() != f.dry.kineticBound())
    return "static friction above kinetic: the peer has Coulomb's law";
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
  // a law without mu (none) is the peer's free platform, mu = 0
  const double mu = sp.friction.valueOr("mu", 0.0);
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
