// metrosync_engine_probe: the direct engine alone, for instruction counts under valgrind
// (tools/bench/instructions.sh). `metrosync_engine_probe RIG K [KEY=VALUE ...]` runs the rig K
// times without samples (as the bench's final-state timings do) and prints the counts and the
// final state; `metrosync_engine_probe RIG --peer-args` prints the careful peer's arguments for
// the same scene (tools/bench/peer_scene.h). Instructions per run: the count of K = 3 less that
// of K = 1, halved (start-up and loading cancel).
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "sim/engines/direct/direct_engine.h"
#include "tools/bench/bench_run.h"
#include "tools/bench/peer_scene.h"
#include "yaml/rig_loader.h"

namespace {

using namespace metrosync;

struct NoSamples : RunSink {
  bool wantsTrajectory() const override { return false; }
  bool wantsEnvelope() const override { return false; }
  bool wantsEventRows() const override { return false; }
};

int printPeerArguments(const std::string& rig) {
  for (const std::string& a : bench::peerSceneArguments(bench::loadScene(rig)))
    std::printf("%s\n", a.c_str());
  return 0;
}

int runEngine(const std::string& path, int runs, const std::vector<std::string>& overrides) {
  const Rig rig = loadRigFile(path, overrides);
  RunReport r;
  for (int k = 0; k < runs; ++k) {
    NoSamples sink;
    r = runDirectModel(rig, sink);
  }
  std::printf("steps %ld evals %ld events %ld final", r.counts.steps, r.counts.rhs_evals,
              r.counts.events);
  for (double v : r.final_trajectory_row) std::printf(" %.17g", v);
  std::printf("\n");
  return r.complete ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s RIG K [KEY=VALUE ...] | RIG --peer-args\n", argv[0]);
    return 2;
  }
  try {
    if (std::string(argv[2]) == "--peer-args") return printPeerArguments(argv[1]);
    return runEngine(argv[1], std::atoi(argv[2]), std::vector<std::string>(argv + 3, argv + argc));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
