// The files of `metrosync basin` (the drawing and the statistics: sim/analysis/basin.h):
//   basin.csv   one row per sample, in sample order: sample, the drawn values (one column per
//               --random key, as given to the rig), regime, A_1..A_N, psi_2..psi_N (final, psi
//               in [0, 2 pi)), complete (1/0)
//   basin.json  what was drawn (rig, --set, model, engine, seed, samples, keys) and the fraction
//               of each regime with its 95% Wilson interval
//   basin.png   with two --random keys: the samples in the plane of the two keys, one colour
//               per regime (the sweep's colours), a map of the basins
// and the table printed on stdout.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/analysis/basin.h"
#include "sim/analysis/sweep.h"
#include "tools/report/outputs.h"

namespace metrosync {

// One sample: the values drawn (their texts, as given to the rig) and its outcome.
struct BasinSample {
  std::vector<std::string> drawn;  // (keys x 1)
  SweepPoint point;                // point.index is the sample number
};

std::string basinCsvHeader(const std::vector<RandomKey>& keys, int n);
std::string basinCsvRow(const BasinSample& s);
// header + the rows of `samples` in sample order
std::string basinCsv(const std::vector<RandomKey>& keys, int n,
                     const std::map<long, BasinSample>& samples);

// The "fractions" array of basin.json: [{regime, count, fraction, ci95: [lo, hi]}].
nlohmann::json fractionsJson(const std::vector<RegimeFraction>& fractions);
// The "random" array: [{key, spec, from, to, angle}].
nlohmann::json randomKeysJson(const std::vector<RandomKey>& keys);

// The table on stdout: regime, count, fraction, 95% interval; one line each.
std::string fractionsTable(const std::vector<RegimeFraction>& fractions, long samples);

// basin.png for two keys (keys[0] across, keys[1] up); returns true when written.
bool plotBasinMap(const OutputDir& dir, const std::vector<RandomKey>& keys,
                  const std::map<long, BasinSample>& samples, const std::string& title);

}  // namespace metrosync
