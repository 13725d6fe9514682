// metrosync_network_bench RIG [DURATION_S]: the direct engine's cost per fast period on a network
// rig (docs/networks.md, issue 13), engine only (no file is written): prints the metronomes, the
// fast periods run, the wall time, the steps and the cost per period.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "sim/engines/direct/direct_engine.h"
#include "yaml/network_loader.h"

namespace {
struct NullSink : metrosync::StateSink {
  void stateSample(double, const std::vector<double>&,
                   const std::vector<metrosync::PlatformMode>&) override {}
};
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: metrosync_network_bench RIG [DURATION_S]\n");
    return 2;
  }
  std::vector<std::string> sets;
  if (argc > 2) sets.push_back(std::string("simulation.duration=") + argv[2]);
  const metrosync::Network net = metrosync::loadNetworkFile(argv[1], sets);
  NullSink sink;
  const auto t0 = std::chrono::steady_clock::now();
  const metrosync::RunReport rep = metrosync::runDirect(net, sink);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double periods = net.sim.t_end_s / rep.fast_period_s;
  std::printf("metronomes %d periods %.1f wall %.3f s steps %ld rhs %ld cost/period %.3g ms\n",
              net.numMetronomes(), periods, wall, rep.counts.steps, rep.counts.rhs_evals,
              1e3 * wall / periods);
  return rep.complete ? 0 : 3;
}
