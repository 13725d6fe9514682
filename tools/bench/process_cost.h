// The whole `metrosync run` process against its own wall_seconds (issue 36), and where each
// millisecond goes: `metrosync run RIG --quiet --no-plot --out TMP` with METROSYNC_PHASES=1,
// K times after one run that warms the page cache and is not counted; each run timed from
// outside (its start and end, its CPU), its phases read from its stderr, its wall_seconds from
// summary.json (tools/bench/process_phases.h does the arithmetic).
#pragma once

#include <string>
#include <vector>

#include "tools/bench/bench_measure.h"
#include "tools/bench/process_phases.h"

namespace metrosync::bench {

struct ProcessOptions {
  std::string metrosync = "build/metrosync";
  std::string scene = "yaml/rigs/bench/peer-n2.yaml";  // the careful peer's own scene
  int repeat = 21;
};

struct ProcessMeasurement {
  ProcessBreakdown breakdown;
  std::string command;  // one run's (its --out left out)
  std::string failure;  // "" when every run succeeded
  double load_min = 0.0, load_max = 0.0;
};

ProcessMeasurement measureProcess(const ProcessOptions& o, const BenchOptions& c);

}  // namespace metrosync::bench
