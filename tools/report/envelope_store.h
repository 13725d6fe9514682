// `sweep --keep envelope`: every grid point's envelope rows in one gzip-compressed CSV per sweep
// folder (per shard), DIR/envelopes.csv.gz (docs/sweep-points.md):
//   point,tau,A_1..A_N,psi_2..psi_N,r      one line per envelope row, as `run` writes envelope.csv
//   #end,POINT,ROWS                        after the last row of a point (its rows are complete)
// Points are written in the order they finish (several threads), each as its own gzip member
// (concatenated members are one gzip stream: zcat, Python's gzip read them whole). A point counts
// only with its #end line, so rows of a point cut short by a kill are ignored (it is redone on
// --resume); a point written twice has the same rows (the runs are deterministic): the last wins.
#pragma once

#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "sim/record/finite_check.h"

namespace metrosync {

constexpr const char* kEnvelopeStoreName = "envelopes.csv.gz";

// Header line of the store for N metronomes: point,tau,A_1..A_N,psi_2..psi_N,r
std::string envelopeStoreHeader(int n);

// The complete points of a store: point -> its envelope lines without the point column (the
// format of envelope.csv's rows). A truncated or damaged tail is ignored; a missing file is empty.
// Throws std::runtime_error when the header is not a store's.
std::map<long, std::vector<std::string>> readEnvelopeStore(const std::string& path);
// ... visited one point at a time, in the order of the file (the rows of one point in memory).
void forEachStoredEnvelope(const std::string& path,
                           const std::function<void(long, const std::vector<std::string>&)>& visit);

// Appends points to DIR/envelopes.csv.gz. fresh: a new file with the header; otherwise the
// complete points already there that are in `keep` (the points regimes.csv has; the others run
// again) are kept: the file is rewritten without them and without a damaged tail first, one point
// at a time.
class EnvelopeStore {
 public:
  EnvelopeStore(const std::string& path, int n, bool fresh,
                const std::function<bool(long)>& keep = {});
  // rows: envelope.csv lines (formatEnvelopeRow) of point g; thread-safe
  void append(long g, const std::vector<std::string>& rows);

 private:
  std::string path_;
  std::mutex mutex_;
  CsvCheck check_;  // every row appended
};

}  // namespace metrosync
