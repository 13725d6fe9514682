// A sweep from code (docs/library.md): the regime of a rig over a range of one key, on two
// threads, each point run on the direct engine and judged as `metrosync sweep` judges it.
//
//   sweep_mu RIG.yaml KEY=FROM:TO:COUNT
//
// prints one line per point: its index, the key's value, its regime. Built against the installed
// package (find_package(metrosync), examples/CMakeLists.txt).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "models/scaling.h"
#include "sim/analysis/sweep.h"
#include "sim/analysis/sweep_run.h"
#include "sim/engines/engine.h"
#include "yaml/rig_loader.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: sweep_mu RIG.yaml KEY=FROM:TO:COUNT\n");
    return 2;
  }
  try {
    const std::string rig_path = argv[1];
    const metrosync::SweepGrid grid({metrosync::parseVary(argv[2])});
    // each point: the rig file with the point's KEY=VALUE, on the direct engine
    auto make_point = [&](long g) {
      metrosync::PointInput in;
      in.rig = metrosync::loadRigFile(rig_path, grid.overrides(g));
      in.scaled = metrosync::computeScaled(in.rig);
      in.engine = metrosync::findEngine("direct");
      return in;
    };
    const std::vector<metrosync::SweepPoint> rows = metrosync::runSweep(grid, make_point, 2);
    for (const metrosync::SweepPoint& p : rows)
      std::printf("%ld %s %s\n", p.index, grid.axes()[0].text(p.index).c_str(), p.regime.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sweep_mu: %s\n", e.what());
    return 2;
  }
}
