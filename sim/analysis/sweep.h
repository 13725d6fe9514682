// Sweeps (SPEC section 2 `sweep`, section 3 regimes.csv): a grid of runs over one or two rig keys,
// run in parallel, streamed to regimes.csv as points finish, resumable, and splittable into
// shards that `merge` joins again. No model and no rig loader in here: the command
// (tools/cli/sweep.cpp) says how one grid point runs; this file owns the grid, the file formats
// and the scheduling.
//
//   grid       --vary KEY=FROM:TO:COUNT, COUNT values from FROM to TO, both included (":open"
//              after COUNT leaves TO out: [FROM, TO), for angles); FROM and TO may be written with
//              pi ("2pi", "pi/2", "-0.5*pi"). Grid index g = i_1 * COUNT_2 + i_2: the first --vary
//              is the slow (outer) one.
//   shards     --shard K/N runs the points with g mod N == K - 1.
//   regimes.csv  one line per point (SPEC 3): the varied keys' values as given to the rig, regime,
//              A_1..A_N, psi_2..psi_N (final, psi wrapped to [0, 2 pi)), then r (order parameter),
//              s (drive strength |Z| / mu of a Coulomb platform), clusters ("3+2"), tau (of the
//              final row), complete (1/0), index (g), message (why a failed point failed;
//              CSV-quoted when it must be).
//   sweep.json the manifest: what was swept (rig text, --set, model, grid), so that --resume and
//              merge can check they continue or join the same sweep, and how far it got.
//
// Every point's row depends only on the point (each run builds its own model, nothing is shared
// between threads), so regimes.csv, once sorted, is the same bit for bit for any --jobs and any
// split into shards.
#pragma once

#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace metrosync {

// A bad --vary / --shard, or manifests and files that do not belong together: the command line's
// fault (exit 2).
struct SweepInputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// ---- the grid -----------------------------------------------------------------------------------

struct SweepAxis {
  std::string key;   // rig key path, e.g. platform.friction.mu
  std::string spec;  // FROM:TO:COUNT[:open] as given
  double from = 0.0, to = 0.0;
  long count = 0;
  bool open = false;               // TO left out
  std::vector<double> values;      // (count x 1), exactly the numbers the texts below denote
  std::vector<std::string> texts;  // (count x 1) the values as written to the rig and regimes.csv
};

// "KEY=FROM:TO:COUNT[:open]"; throws SweepInputError saying what is wrong.
SweepAxis parseVary(const std::string& text);

// A number, or a multiple of pi: "1.5", "-2e-3", "pi", "2pi", "2*pi", "-pi/2", "0.5pi/3".
// Throws SweepInputError.
double parseSweepNumber(const std::string& text);

// The value of a grid point as text (%.15g); the point's value is the number it denotes.
std::string sweepValueText(double v);

class SweepGrid {
 public:
  SweepGrid() = default;
  // 1 or 2 axes with distinct keys (SPEC: "one or two keys"); throws SweepInputError.
  explicit SweepGrid(std::vector<SweepAxis> axes);

  const std::vector<SweepAxis>& axes() const { return axes_; }
  long size() const { return size_; }
  // (axes x 1) position of point g on each axis
  std::vector<long> coordinates(long index) const;
  // "KEY=VALUE" for point g, one per axis, for the rig loader
  std::vector<std::string> overrides(long index) const;

  // {"axes": [{key, spec, from, to, count, open, values: [texts]}], "points": size}
  nlohmann::json toJson() const;
  static SweepGrid fromJson(const nlohmann::json& j);  // throws SweepInputError

 private:
  std::vector<SweepAxis> axes_;
  long size_ = 0;
};

struct SweepShard {
  int k = 1, n = 1;  // the K-th of N, K from 1
  bool contains(long index) const { return index % n == k - 1; }
  std::string text() const { return std::to_string(k) + "/" + std::to_string(n); }
};
// "K/N" with 1 <= K <= N; throws SweepInputError.
SweepShard parseShard(const std::string& text);

// The grid indices of a shard, ascending.
std::vector<long> shardIndices(const SweepGrid& grid, const SweepShard& shard);

// ---- regimes.csv --------------------------------------------------------------------------------

// One grid point's outcome.
struct SweepPoint {
  long index = 0;
  std::string regime;       // a name from sim/analysis/regime.h, or "failed"
  std::vector<double> A;    // (N x 1) final amplitudes
  std::vector<double> psi;  // (N-1 x 1) final phase differences, wrapped to [0, 2 pi)
  double r = std::numeric_limits<double>::quiet_NaN();  // final order parameter
  // final drive strength of a Coulomb platform, s = |sum_j A_j e^{i phi_j}| / mu (e3.1): s <= 1
  // the platform is stuck and couples nothing; inf for mu = 0, NaN for the other laws
  double s = std::numeric_limits<double>::quiet_NaN();
  std::string clusters;                                   // "3+2": clusters of the alive metronomes
  double tau = std::numeric_limits<double>::quiet_NaN();  // tau of the final row
  bool complete = true;                                   // false: the run failed (regime "failed")
  std::string message;                                    // why it failed
  double wall_seconds = 0.0;  // not in regimes.csv (it changes from run to run): timings.csv
};

// psi wrapped to [0, 2 pi)
double wrapToTwoPi(double angle_rad);

std::vector<std::string> regimesColumns(const SweepGrid& grid, int n);
std::string regimesHeader(const SweepGrid& grid, int n);
// One line (no newline); the key columns are the axes' texts of the point.
std::string formatRegimesRow(const SweepGrid& grid, const SweepPoint& p);
// Reads a line written by formatRegimesRow (for a sweep of N metronomes); throws
// SweepInputError when it is not one (wrong column count, bad number, index off the grid, key
// values that are not the point's).
SweepPoint parseRegimesRow(const SweepGrid& grid, int n, const std::string& line);

// The rows of a regimes.csv: the line of each index (first one wins) and its parsed point.
struct RegimesTable {
  std::map<long, std::string> lines;
  std::map<long, SweepPoint> points;
  long partial_lines = 0;    // a last line cut short (kill -9 mid-write): dropped
  long malformed_lines = 0;  // complete lines that do not parse: dropped (their points rerun)
  long duplicate_lines = 0;  // an index seen again: dropped
  std::vector<std::string> warnings;
  size_t complete_bytes = 0;  // length of the file up to its last newline
};
// Reads `path`; throws SweepInputError when its header is not `regimesHeader(grid, n)`.
// A missing file gives an empty table.
RegimesTable readRegimesCsv(const std::string& path, const SweepGrid& grid, int n);

// Writes header + lines (ascending index) to `path` atomically.
void writeSortedRegimesCsv(const std::string& path, const SweepGrid& grid, int n,
                           const std::map<long, std::string>& lines);

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
  void append(const std::string& line);  // line + '\n'; throws std::runtime_error
  void close();

 private:
  std::string path_;
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

// Reads DIR/sweep.json; throws SweepInputError when it is missing or is not a sweep manifest.
nlohmann::json readSweepJson(const std::string& path);

// ---- running ------------------------------------------------------------------------------------

// Runs run_point(g) for every g in `todo` (in that order of dispatch) on `jobs` threads. Each
// result is handed to `finished` under a lock, in completion order; run_point returns nullopt for
// a point that was interrupted (not recorded). No new point starts once stop() is true.
// Exceptions from run_point or finished stop the sweep and are rethrown (the first one).
void runSweepPoints(const std::vector<long>& todo, int jobs,
                    const std::function<std::optional<SweepPoint>(long)>& run_point,
                    const std::function<void(const SweepPoint&)>& finished,
                    const std::function<bool()>& stop);

// "[#########-----------]  1234/10000  12%  35.2 points/s  ETA 4:09  3 failed", fitted to `width`
// characters. eta_s < 0: unknown.
std::string progressText(long done, long total, long failed, double rate_per_s, double eta_s,
                         int width);

}  // namespace metrosync
