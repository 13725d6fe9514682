#include "tools/cli/network_sweep.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "sim/analysis/network_verdict.h"
#include "tools/cli/commands.h"
#include "tools/cli/engines.h"
#include "yaml/network_loader.h"

namespace metrosync::cli {

std::optional<Network> loadSweepNetwork(const std::string& text, const std::string& display_name,
                                        const std::vector<std::string>& overrides) {
  if (!isNetworkText(text)) return std::nullopt;
  LoadOptions lo;  // as `run` on a network: every engine's integrators
  for (const Engine* e : engines())
    for (const std::string& n : e->integrators()) lo.integrators.push_back(n);
  lo.integrator_help = "one of: " + integratorHelp();
  Network net = loadNetworkText(text, display_name, overrides, lo);
  if (net.isSingleRig()) return std::nullopt;
  return net;
}

Rig networkSweepRig(const Network& net) {
  Rig rig = net.platforms.at(0).rig;
  rig.name = net.name;
  rig.metronomes.clear();
  for (const NetworkPlatform& p : net.platforms)
    rig.metronomes.insert(rig.metronomes.end(), p.rig.metronomes.begin(), p.rig.metronomes.end());
  return rig;
}

const Engine& networkSweepEngine(const std::string& requested, const std::string& model,
                                 const Network& net, const std::string& display_name) {
  const std::string what = "a network of " + std::to_string(net.platforms.size()) + " platforms";
  if (model == "slow")
    throw UsageError("--model slow: the slow flow is single-platform; " + what +
                     " sweeps the full model only (--engine direct or simbody)");
  const Engine& e = chooseEngine(requested, requested.empty() ? "full" : model,
                                 net.platforms.at(0).rig, display_name);
  if (!e.runsNetworks())
    throw UsageError("--engine " + e.name() + ": " + what +
                     " sweeps the full model only (--engine direct or simbody)");
  return e;
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
