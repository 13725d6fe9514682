// What a sweep reports (tools/cli/sweep.h): the console's summary lines and sweep.json's status,
// shared by sweep, merge and the run stage.
#pragma once

#include <chrono>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/thread_cpu_time.h"  // threadCpuSeconds: a point runs on one thread
#include "sim/analysis/sweep.h"
#include "tools/report/outputs.h"
#include "tools/report/sweep_files.h"

namespace metrosync::cli {

using SweepClock = std::chrono::steady_clock;
double secondsSince(SweepClock::time_point t0);
std::string joined(const std::vector<std::string>& v, const std::string& sep = ", ");
const char* modelTitle(const std::string& model);  // "full model", "slow flow"

// What a sweep has done, without its rows (those are in regimes.csv, on disk): the memory of a
// sweep does not grow with its points (issue 29).
struct SweepTally {
  long done = 0, failed = 0;
  std::map<std::string, long> regimes;  // points per regime
  void add(const SweepPoint& p);
};
SweepTally tallyOf(const std::map<long, SweepPoint>& points);

std::string countsText(const SweepTally& tally);  // "in-phase 3, antiphase 1"
std::string gridText(const SweepGrid& grid);      // "100 x 100 = 10000 points"
std::string mapTitle(const SweepManifest& m);
void writeSweepJson(const OutputDir& dir, const nlohmann::json& j);
nlohmann::json statusJson(const SweepManifest& m, long shard_points, const SweepTally& tally,
                          bool complete);

}  // namespace metrosync::cli
