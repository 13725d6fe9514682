#include "tools/cli/sweep_summary.h"

#include <time.h>

#include <cstdio>

#include "base/number_text.h"
#include "sim/record/atomic_file.h"
#include "tools/report/json_file.h"
#include "tools/report/sweep_maps.h"

namespace metrosync::cli {

double secondsSince(SweepClock::time_point t0) {
  return std::chrono::duration<double>(SweepClock::now() - t0).count();
}

// CPU seconds of the calling thread (a point runs on one thread): on a shared machine the measure
// of what a point costs, where wall time also counts the other processes.
std::string joined(const std::vector<std::string>& v, const std::string& sep) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

const char* modelTitle(const std::string& model) {
  return model == "full" ? "full model" : "slow flow";
}

void SweepTally::add(const SweepPoint& p) {
  ++done;
  failed += !p.complete;
  ++regimes[p.regime];
}

SweepTally tallyOf(const std::map<long, SweepPoint>& points) {
  SweepTally t;
  for (const auto& [g, p] : points) t.add(p);
  return t;
}

std::string countsText(const SweepTally& tally) {
  std::string s;
  for (const auto& name : regimeLegendOrder(tally.regimes))
    s += (s.empty() ? "" : ", ") + name + " " + std::to_string(tally.regimes.at(name));
  return s.empty() ? "none yet" : s;
}

// "100 x 100 = 10000 points", "40 points"
std::string gridText(const SweepGrid& grid) {
  std::string s;
  for (const auto& a : grid.axes()) s += (s.empty() ? "" : " x ") + std::to_string(a.count);
  if (grid.axes().size() > 1) s += " = " + std::to_string(grid.size());
  return s + (grid.size() == 1 ? " point" : " points");
}

std::string mapTitle(const SweepManifest& m) {
  return m.rig_name + " - " + modelTitle(m.model) +
         (m.model == "full" ? " (" + m.engine + ")" : "") + ", N = " + std::to_string(m.metronomes);
}

void writeSweepJson(const OutputDir& dir, const nlohmann::json& j) {
  writeJsonFile(dir.file("sweep.json"), j);
}

nlohmann::json statusJson(const SweepManifest& m, long shard_points, const SweepTally& tally,
                          bool complete) {
  nlohmann::json j = m.toJson();
  j["complete"] = complete;
  j["points"] = {{"grid", m.grid.size()},
                 {"this_run", shard_points},
                 {"done", tally.done},
                 {"failed", tally.failed},
                 {"missing", shard_points - tally.done}};
  nlohmann::json counts = nlohmann::json::object();
  for (const auto& [name, k] : tally.regimes) counts[name] = k;
  j["regimes"] = counts;
  return j;
}

}  // namespace metrosync::cli
