// Lines sorted by an index with memory bounded by a fixed size, whatever their number (issue 29):
// an external merge sort. Lines are buffered up to kSortChunkBytes, each full buffer is sorted and
// written as a run file into a private temporary folder (sim/record/private_dir.h), and the runs
// are merged (at most kSortFanIn at a time, in levels) as they are read back. A sweep's
// regimes.csv, a merge of shards and a basin's samples go through it.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace metrosync {

class PrivateDir;

// Bytes of lines held before a run is written: ~5000 rows of a sweep of two metronomes. A sweep of
// 10^7 points (~2 GB of rows) makes ~2000 runs, merged in two levels of kSortFanIn.
constexpr std::size_t kSortChunkBytes = std::size_t(1) << 20;
// Runs merged at once (open files while merging).
constexpr std::size_t kSortFanIn = 64;

// The folder for runs when no output folder exists yet: $TMPDIR, or /tmp.
std::string temporaryFolder();

class ExternalSort {
 public:
  // Runs go into a new private folder in `folder`.
  explicit ExternalSort(const std::string& folder, std::size_t chunk_bytes = kSortChunkBytes);
  ExternalSort(const ExternalSort&) = delete;
  ExternalSort& operator=(const ExternalSort&) = delete;
  ~ExternalSort();

  // A line (no newline in it) with its index. Throws std::runtime_error on a write error.
  void add(long index, std::string line);
  // Every line added, in ascending index; lines of one index in the order they were added. May be
  // called again (no add() in between is needed). Throws std::runtime_error on a read error.
  void forEach(const std::function<void(long, const std::string&)>& visit);
  // ... grouped: visit(index, its lines in the order added).
  void forEachIndex(const std::function<void(long, const std::vector<std::string>&)>& visit);

  // The most lines held in memory at once (tests: that it does not grow with the lines).
  std::size_t maxLinesHeld() const { return max_held_; }

 private:
  void spill();
  void mergeDown();  // merges runs until at most kSortFanIn are left
  std::string folder_;
  std::unique_ptr<PrivateDir> tmp_;  // made at the first run
  std::size_t chunk_bytes_, bytes_ = 0, max_held_ = 0;
  long next_run_ = 0;
  std::vector<std::pair<long, std::string>> chunk_;
  std::vector<std::string> runs_;  // run files in the private folder, in the order made
};

}  // namespace metrosync
