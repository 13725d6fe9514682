// The files of a sweep (their format: sim/analysis/sweep.h): regimes.csv rows, the table of a
// regimes.csv read back for --resume and merge, the appender that streams rows as points finish,
// the sweep.json manifest, and the progress line.
#pragma once

#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "sim/analysis/sweep.h"
#include "sim/record/finite_check.h"
#include "tools/report/external_sort.h"

namespace metrosync {

// ---- regimes.csv --------------------------------------------------------------------------------

std::vector<std::string> regimesColumns(const SweepGrid& grid, int n);
std::string regimesHeader(const SweepGrid& grid, int n);
// One line (no newline); the key columns are the axes' texts of the point.
std::string formatRegimesRow(const SweepGrid& grid, const SweepPoint& p);
// Reads a line written by formatRegimesRow (for a sweep of N metronomes); throws
// SweepInputError when it is not one (wrong column count, bad number, index off the grid, key
// values that are not the point's).
SweepPoint parseRegimesRow(const SweepGrid& grid, int n, const std::string& line);

// What reading a regimes.csv found besides its rows.
struct RegimesScan {
  long partial_lines = 0;    // a last line cut short (kill -9 mid-write): dropped
  long malformed_lines = 0;  // complete lines that do not parse: dropped (their points rerun)
  long duplicate_lines = 0;  // an index seen again: dropped
  std::vector<std::string> warnings;
  size_t complete_bytes = 0;  // length of the file up to its last newline
};
// Called with each well-formed row as it is read (none held); returns false for a row it drops
// as a duplicate (counted in duplicate_lines).
using RegimesVisitor = std::function<bool(SweepPoint, const std::string& line)>;
// Reads `path` line by line; throws SweepInputError when its header is not
// `regimesHeader(grid, n)`. A missing file visits nothing. `dropped` says in the warnings what
// becomes of a point whose line is dropped ("the point runs again" for --resume; merge runs
// nothing).
RegimesScan scanRegimesCsv(const std::string& path, const SweepGrid& grid, int n,
                           const std::string& dropped, const RegimesVisitor& visit);

// The rows of a regimes.csv held in memory (small sweeps: `figures`, tests): the line of each
// index (first one wins) and its parsed point.
struct RegimesTable : RegimesScan {
  std::map<long, std::string> lines;
  std::map<long, SweepPoint> points;
};
RegimesTable readRegimesCsv(const std::string& path, const SweepGrid& grid, int n,
                            const std::string& dropped = "the point runs again");

// The grid index of a regimes.csv line (nullopt: malformed).
std::optional<long> regimesRowIndex(const SweepGrid& grid, int n, const std::string& line);

// Visits the points of the regimes.csv at `path` in the order of its lines, one at a time (none
// held); malformed lines and a last line cut short are skipped, a missing file visits none. Lines
// `wanted` refuses are skipped unparsed.
void forEachRegimesRow(const std::string& path, const SweepGrid& grid, int n,
                       const std::function<void(const SweepPoint&)>& visit,
                       const std::function<bool(const std::string&)>& wanted = {});

// Rewrites `path` (regimes.csv with its rows in the order they finished: perhaps an earlier run's
// rows, a row given again by a re-run point, a malformed line) sorted by grid index, each index
// once (its last row), for the indices `keep` accepts, malformed lines dropped. Through an
// external sort holding at most `chunk_bytes` of rows (tools/report/external_sort.h), so that
// memory does not grow with the sweep (issue 29). Atomic (sim/record/atomic_file.h).
void sortRegimesCsv(const std::string& path, const SweepGrid& grid, int n,
                    const std::function<bool(long)>& keep,
                    std::size_t chunk_bytes = kSortChunkBytes);

// ---- timings.csv --------------------------------------------------------------------------------

// How long each point took, a line per point as it finishes (docs/bench/sweep-throughput.md):
// "index,wall_seconds,cpu_seconds,engine_cpu_seconds": wall and CPU seconds of the whole point
// (rig loaded, run, judged) and the CPU seconds inside the engine's run; an unknown time (a
// network's engine time) is an empty field.
std::string timingsHeader();
std::string formatTimingsRow(const SweepPoint& p);
// --resume: how many bytes of the timings.csv at `path` to keep before appending (its whole
// lines; 0 when absent: start afresh). A file of an older layout (another header: "index,
// wall_seconds") is first rewritten in this one, atomically, its rows' new columns empty.
size_t resumableTimingsBytes(const std::string& path);

// Appends whole lines to regimes.csv as points finish: one write(2) per line on an O_APPEND
// descriptor, so that a kill at any moment leaves whole lines and at most one cut-off last line.
class RegimesAppender {
 public:
  // Creates `path` with `header` (fresh = true), or opens it for appending after cutting it to
  // `keep_bytes` (drops a cut-off last line). Throws std::runtime_error.
  RegimesAppender(const std::string& path, const std::string& header, bool fresh,
                  size_t keep_bytes);
  RegimesAppender(const RegimesAppender&) = delete;
  RegimesAppender& operator=(const RegimesAppender&) = delete;
  ~RegimesAppender();
  // line + '\n'; throws std::runtime_error, NonFiniteOutput for a non-finite number in it
  void append(const std::string& line);
  void close();

 private:
  void put(const std::string& line);

  std::string path_;
  CsvCheck check_;
  int fd_ = -1;
};

// ---- sweep.json ---------------------------------------------------------------------------------

struct SweepManifest {
  std::string model;     // "slow" | "full"
  std::string engine;    // "slowflow", or the full model's: "direct" | "simbody"
  std::string rig_path;  // as given ("" = the built-in rig)
  std::string rig_name;
  std::string rig_text;           // the rig file's text: what was swept
  std::vector<std::string> sets;  // --set, in order
  int metronomes = 0;
  SweepGrid grid;
  SweepShard shard;
  bool merged = false;  // written by merge

  nlohmann::json toJson() const;
  static SweepManifest fromJson(const nlohmann::json& j);  // throws SweepInputError
};

// Empty when `a` and `b` describe the same grid of runs (model, engine, rig text, --set, grid,
// N), else
// what differs.
std::string sweepDifference(const SweepManifest& a, const SweepManifest& b);

// DIR/sweep.json as a manifest; every error names the file.
SweepManifest readSweepManifest(const std::string& dir);

// Reads DIR/sweep.json; throws SweepInputError when it is missing or is not a sweep manifest.
nlohmann::json readSweepJson(const std::string& path);

// "[#########-----------]  1234/10000  12%  35.2 points/s  ETA 4:09  3 failed", fitted to `width`
// characters. eta_s < 0: unknown.
std::string progressText(long done, long total, long failed, double rate_per_s, double eta_s,
                         int width);

}  // namespace metrosync
