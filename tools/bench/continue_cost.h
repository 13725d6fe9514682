// `metrosync continue --all` at N = 32 (issue 36): the whole process's wall and CPU time (from
// outside, the median of K runs) of `metrosync continue RIG --param platform.friction.mu --to
// 0.01 --all -q --out TMP` on each rig, the points of its branches; target <= 20 s of wall time
// on 2 cores. A run stopped by --timeout says so (its time: more than the timeout).
#pragma once

#include <string>
#include <vector>

#include "tools/bench/bench_measure.h"
#include "tools/bench/speed_targets.h"

namespace metrosync::bench {

struct ContinueCostOptions {
  std::string metrosync = "build/metrosync";
  std::vector<std::string> rigs = {"yaml/rigs/bench/n32.yaml", "yaml/rigs/n32.yaml"};
  std::vector<std::string> args = {"--param", "platform.friction.mu", "--to", "0.01", "--all"};
  int repeat = 1;
  double timeout_s = 0;  // 0: none
};

struct ContinueCostRow {
  std::string rig, command;
  int runs = 0;
  double wall_s = 0.0, cpu_s = 0.0;  // medians
  long points = 0;                   // rows of branches.csv (the last run's)
  bool timed_out = false;
  std::string failure;  // "" when every run finished with exit 0
  double load_min = 0.0, load_max = 0.0;
};

std::vector<ContinueCostRow> measureContinueCost(const ContinueCostOptions& o,
                                                 const BenchOptions& c);

std::string continueCostCsv(const std::vector<ContinueCostRow>& rows);
std::string continueCostMarkdown(const std::vector<ContinueCostRow>& rows);

}  // namespace metrosync::bench
