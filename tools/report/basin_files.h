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

#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/analysis/basin.h"
#include "sim/analysis/sweep.h"
#include "tools/report/external_sort.h"
#include "tools/report/outputs.h"

namespace metrosync {

// One sample: the values drawn (their texts, as given to the rig) and its outcome.
struct BasinSample {
  std::vector<std::string> drawn;  // (keys x 1)
  SweepPoint point;                // point.index is the sample number
};

std::string basinCsvHeader(const std::vector<RandomKey>& keys, int n);
std::string basinCsvRow(const BasinSample& s);

// The samples as they finish (in any order): their rows go to an external sort
// (tools/report/external_sort.h) in the system's temporary folder, and only the count of each
// regime stays in memory, so that a basin's memory does not grow with its samples (issue 29).
class BasinRows {
 public:
  BasinRows();
  void add(const BasinSample& s);
  long added() const { return added_; }
  // Counts the samples (each index once) for the three below.
  void tally();
  long count() const { return count_; }
  long failed() const { return failed_; }
  const std::map<std::string, long>& regimes() const { return regimes_; }
  // header + the rows in sample order, written atomically to `path`
  void writeCsv(const std::string& path, const std::vector<RandomKey>& keys, int n);
  // visit(csv row, regime) in sample order
  void forEach(const std::function<void(const std::string&, const std::string&)>& visit);

 private:
  ExternalSort rows_;  // "REGIME\tCSV ROW" by sample
  std::map<std::string, long> regimes_;
  long added_ = 0, count_ = 0, failed_ = 0;
};

// The "fractions" array of basin.json: [{regime, count, fraction, ci95: [lo, hi]}].
nlohmann::json fractionsJson(const std::vector<RegimeFraction>& fractions);
// The "random" array: [{key, spec, from, to, angle}].
nlohmann::json randomKeysJson(const std::vector<RandomKey>& keys);

// The table on stdout: regime, count, fraction, 95% interval; one line each.
std::string fractionsTable(const std::vector<RegimeFraction>& fractions, long samples);

// basin.png for two keys (keys[0] across, keys[1] up); returns true when written.
bool plotBasinMap(const OutputDir& dir, const std::vector<RandomKey>& keys, BasinRows& samples,
                  const std::string& title);

}  // namespace metrosync
