#include "tools/cli/network_sweep.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "sim/analysis/network_verdict.h"

namespace metrosync::cli {

Rig networkSweepRig(const Network& net) {
  Rig rig = net.platforms.at(0).rig;
  rig.name = net.name;
  rig.metronomes.clear();
  for (const NetworkPlatform& p : net.platforms)
    rig.metronomes.insert(rig.metronomes.end(), p.rig.metronomes.begin(), p.rig.metronomes.end());
  return rig;
}

SweepPoint runNetworkSweepPoint(const Network& net, const Engine& engine, long g,
                                const std::optional<std::string>& inject_failure) {
  NetworkVerdict verdict(net);
  NetworkRunReport rep;
  try {
    if (inject_failure) throw std::runtime_error("stopped at t = 0 s: " + *inject_failure);
    rep = engine.runNetwork(net, verdict);
  } catch (const std::exception& e) {
    rep.complete = false;
    rep.failure = e.what();
  }
  const int n = net.numMetronomes();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  SweepPoint p;
  p.index = g;
  p.complete = rep.complete;
  if (!verdict.empty()) {
    const EnvelopeRow& last = verdict.last();
    p.A = last.A;
    for (double v : last.psi) p.psi.push_back(wrapToTwoPi(v));
    p.r = last.r;
    p.tau = last.tau;
  } else {
    p.A.assign(n, nan);
    p.psi.assign(n > 0 ? n - 1 : 0, nan);
  }
  if (rep.complete) {
    p.regime = verdict.label();
    const std::vector<std::string> regimes = verdict.platformRegimes();
    for (std::size_t q = 0; q < regimes.size(); ++q)
      p.clusters += (q ? "|" : "") + net.platforms[q].name + "=" + regimes[q];
  } else {
    p.regime = "failed";
    p.message = rep.failure.empty() ? "the run stopped early" : rep.failure;
  }
  return p;
}

}  // namespace metrosync::cli
