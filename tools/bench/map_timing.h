// The two regime maps of issues 11 and 23, timed as a user runs them: `metrosync sweep` of the
// experiment map (yaml/rigs/experiment-map.yaml: epsilon 0.073, tau 305.6) over the friction mu
// = 0 .. 0.8 and the start phase of metronome 1 phi0 = 0 .. 2 pi (open), --jobs 2, no maps drawn:
//   full  the full model, 64 x 64 points (target kFullMapTargetS)
//   slow  the slow flow, 100 x 100 points (target kSlowMapTargetS)
// Each map R times (median wall; the process's CPU, all its threads, from rusage).
#pragma once

#include <string>
#include <vector>

#include "tools/bench/bench_measure.h"

namespace metrosync::bench {

constexpr double kFullMapTargetS = 45.0;
constexpr double kSlowMapTargetS = 3.0;

struct MapOptions {
  std::string metrosync = "build/metrosync";
  std::string rig = "yaml/rigs/experiment-map.yaml";
  std::vector<std::string> maps = {"full", "slow"};
  int repeat = 1;
  int jobs = 2;
  std::string tmp;  // where the sweeps write ("" = the system's temporary directory)
};

struct MapRow {
  std::string map;  // full | slow
  int points = 0;
  int runs = 0;
  double wall_s = 0.0, cpu_s = 0.0;  // medians
  std::vector<double> walls;         // every run's wall time
  double target_s = 0.0;
  double load_min = 0.0, load_max = 0.0;
  std::string command;  // the sweep's command line (its --out left out)
  std::string failure;
};

// The sweep's arguments for one map (full or slow; std::invalid_argument otherwise).
std::vector<std::string> mapSweepArgs(const MapOptions& o, const std::string& map);

std::vector<MapRow> timeMaps(const MapOptions& o, const BenchOptions& c);

std::string mapsCsv(const std::vector<MapRow>& rows);
std::string mapsMarkdown(const std::vector<MapRow>& rows);

}  // namespace metrosync::bench
