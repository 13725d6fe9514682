// Sweeps (SPEC section 2 `sweep`, section 3 regimes.csv): a grid of runs over any number of rig
// keys, run in parallel, streamed to regimes.csv as points finish, resumable, and splittable into
// shards that `merge` joins again. No model and no rig loader in here: the command
// (tools/cli/sweep.cpp) says how one grid point runs; this file owns the grid, the points and the
// scheduling; tools/report/sweep_files.h writes and reads the files described below.
//
//   grid       --vary KEY=FROM:TO:COUNT, COUNT values from FROM to TO, both included (":open"
//              after COUNT leaves TO out: [FROM, TO), for angles; ":log" spaces them evenly in
//              log(value), 0 < FROM <= TO); FROM and TO may be written with pi ("2pi", "pi/2",
//              "-0.5*pi"); --vary KEY=V1,V2,... lists the values (one or more, as given). A key
//              "metronomes.*.REST" sets metronomes.i.REST of every metronome to the point's value.
//              Any number of --vary (an N-D grid, at most kMaxGridPoints points unless forced).
//              Grid index g = ((i_1 * COUNT_2 + i_2) * COUNT_3 + i_3) ...: the first --vary is
//              the slowest (outer) one.
//   shards     --shard K/N runs the points with g mod N == K - 1.
//   regimes.csv  one line per point (SPEC 3): the varied keys' values as given to the rig, regime,
//              A_1..A_N, psi_2..psi_N (final, psi wrapped to [0, 2 pi)), then r (order parameter),
//              s (drive strength |Z| / mu of a Coulomb platform), clusters ("3+2"), tau (of the
//              final row), [in_phase_fraction (with --basin-samples, SweepGrid::Basin),]
//              complete (1/0), index (g), message (why a failed point failed; CSV-quoted when
//              it must be).
//   sweep.json the manifest: what was swept (rig text, --set, model, grid), so that --resume and
//              merge can check they continue or join the same sweep, and how far it got.
//
// Every point's row depends only on the point (each run builds its own model, nothing is shared
// between threads), so regimes.csv, once sorted, is the same bit for bit for any --jobs and any
// split into shards.
#pragma once

#include <cstdint>
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
  std::string spec;  // FROM:TO:COUNT[:open] or V1,V2,... as given
  double from = 0.0, to = 0.0;
  long count = 0;
  bool open = false;               // TO left out
  bool log = false;                // values evenly spaced in log(value)
  std::vector<double> values;      // (count x 1), exactly the numbers the texts below denote
  std::vector<std::string> texts;  // (count x 1) the values as written to the rig and regimes.csv
};

// "KEY=FROM:TO:COUNT[:open][:log]" or "KEY=V1,V2,..."; throws SweepInputError saying what is
// wrong with the values. KEY is kept as written: the command resolves it against the rig
// (resolveRigKey, yaml/rig_loader.h; docs/keys.md), and the rig loader sets it at each point.
SweepAxis parseVary(const std::string& text);

// More grid points than this need --force (the default cap; a sweep keeps a line per point).
constexpr long kMaxGridPoints = 10000000;
// The hard cap, even with --force.
constexpr long kMaxForcedGridPoints = 1000000000000L;

// A number, or a multiple of pi: "1.5", "-2e-3", "pi", "2pi", "2*pi", "-pi/2", "0.5pi/3".
// Throws SweepInputError.
double parseSweepNumber(const std::string& text);

// The value of a grid point as text (%.15g); the point's value is the number it denotes.
std::string sweepValueText(double v);

class SweepGrid {
 public:
  SweepGrid() = default;
  // One or more axes with distinct keys (as written: keys that differ in writing but set the same
  // rig key, metronomes.*.nu and metronomes.1.nu, are refused by the command, which knows the
  // rig), at most max_points points; throws SweepInputError (saying --force lifts the default cap).
  explicit SweepGrid(std::vector<SweepAxis> axes, long max_points = kMaxGridPoints);

  const std::vector<SweepAxis>& axes() const { return axes_; }

  // sweep --basin-samples S --random KEY=FROM:TO ... [--seed N]: each point also runs S random
  // starts (sample k's draws those of `metrosync basin`, sim/analysis/basin.h, the same at every
  // point) and regimes.csv gets the column in_phase_fraction. S = 0: none.
  struct Basin {
    long samples = 0;
    std::uint64_t seed = 1;
    std::vector<std::string> random;  // KEY=FROM:TO, as given
    bool operator==(const Basin& o) const {
      return samples == o.samples && seed == o.seed && random == o.random;
    }
  };
  const Basin& basin() const { return basin_; }
  void setBasin(Basin b) { basin_ = std::move(b); }
  long size() const { return size_; }
  // (axes x 1) position of point g on each axis
  std::vector<long> coordinates(long index) const;
  // "KEY=VALUE" for point g, one per axis, for the rig loader
  std::vector<std::string> overrides(long index) const;

  // {"axes": [{key, spec, from, to, count, open, log, values: [texts]}], "points": size,
  //  "basin": {samples, seed, random} when samples > 0}
  nlohmann::json toJson() const;
  // throws SweepInputError; any size up to kMaxForcedGridPoints (it was checked when run)
  static SweepGrid fromJson(const nlohmann::json& j);

 private:
  std::vector<SweepAxis> axes_;
  long size_ = 0;
  Basin basin_;
};

// --map KEY1,KEY2 (or one KEY): the positions of the axes a map draws, across then up; empty
// text: the first two axes of more than one value (or axis 0). Throws SweepInputError for a key
// that is not an axis or is named twice.
std::vector<size_t> mapAxes(const SweepGrid& grid, const std::string& text);

struct SweepShard {
  int k = 1, n = 1;  // the K-th of N, K from 1
  bool contains(long index) const { return index % n == k - 1; }
  std::string text() const { return std::to_string(k) + "/" + std::to_string(n); }
};
// "K/N" with 1 <= K <= N; throws SweepInputError.
SweepShard parseShard(const std::string& text);

// The grid indices of a shard, ascending (tests; a sweep never lists them: shardSize and
// SweepShard::contains cost nothing per point).
std::vector<long> shardIndices(const SweepGrid& grid, const SweepShard& shard);
// How many grid points the shard holds.
long shardSize(const SweepGrid& grid, const SweepShard& shard);

// ---- a point ------------------------------------------------------------------------------------

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
  // --basin-samples: the fraction of the point's random starts that end in-phase
  double in_phase_fraction = std::numeric_limits<double>::quiet_NaN();
  bool complete = true;  // false: the run failed (regime "failed")
  std::string message;   // why it failed
  // sweep --keep envelope: the point's envelope rows (formatEnvelopeRow), for the envelope store
  std::vector<std::string> kept_rows;
  // How long the point took (not in regimes.csv: they change from run to run; timings.csv):
  // wall and CPU seconds of the whole point (its rig loaded, run, judged, basin samples
  // included), and the CPU seconds inside the engine's run (NaN when unknown: a network's point)
  double wall_seconds = 0.0;
  double cpu_seconds = 0.0;
  double engine_cpu_seconds = std::numeric_limits<double>::quiet_NaN();
};

// psi wrapped to [0, 2 pi)
double wrapToTwoPi(double angle_rad);

// ---- running ------------------------------------------------------------------------------------

// Runs run_point(g) for every g < grid_size with wanted(g) (dispatched in ascending order) on
// `jobs` threads. Each result is handed to `finished` under a lock, in completion order;
// run_point returns nullopt for a point that was interrupted (not recorded). No new point starts
// once stop() is true. Exceptions from run_point or finished stop the sweep and are rethrown (the
// first one). The indices are handed out one at a time, so memory does not grow with the grid.
// Runs on the pool of sim/parallel/worker_pool.h: never more threads than wanted points, fewer
// when the system refuses more; returns how many ran.
int runSweepPoints(long grid_size, const std::function<bool(long)>& wanted, int jobs,
                   const std::function<std::optional<SweepPoint>(long)>& run_point,
                   const std::function<void(const SweepPoint&)>& finished,
                   const std::function<bool()>& stop);
// ... for the indices of `todo`, in that order.
int runSweepPoints(const std::vector<long>& todo, int jobs,
                   const std::function<std::optional<SweepPoint>(long)>& run_point,
                   const std::function<void(const SweepPoint&)>& finished,
                   const std::function<bool()>& stop);

}  // namespace metrosync
