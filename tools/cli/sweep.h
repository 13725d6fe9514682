// `metrosync sweep` and `metrosync merge` (SPEC section 2): regime maps over one or two rig keys,
// run in parallel, resumable, in shards that merge joins. The grid, the points and the scheduling
// are sim/analysis/sweep.h, the files tools/report/sweep_files.h, the maps
// tools/report/sweep_maps.h; this is the command line and how one point runs.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sim/analysis/sweep.h"

namespace metrosync::cli {

struct SweepOptions {
  std::string rig_path;           // empty: the built-in default rig
  std::vector<std::string> sets;  // --set KEY=VALUE, in order
  std::vector<std::string> vary;  // --vary KEY=FROM:TO:COUNT[:open][:log] or KEY=V1,V2,..
  bool force = false;             // --force: more than kMaxGridPoints points
  std::string map;                // --map KEY1,KEY2: the axes of the maps (default: the first two)
  long basin_samples = 0;         // --basin-samples S: random starts per point (0: none)
  std::vector<std::string> random;  // --random KEY=FROM:TO (with --basin-samples)
  std::uint64_t seed = 1;           // --seed N (with --basin-samples)
  std::string out;                  // --out DIR; empty: runs/<rig name>-sweep (-merge)
  bool quiet = false;
  bool no_plot = false;     // sweep: --no-plot, no maps
  bool boundaries = false;  // sweep: --boundaries, the slow flow's fold and Hopf curves
  std::string model;        // slow | full; empty: the --engine's model, else slow
  std::string engine;       // a registry name (sim/engines/engine.h); empty: the model's default
  int jobs = 0;             // worker threads; 0: the number of cores
  bool resume = false;
  std::string shard;                // "K/N"; empty: the whole grid
  std::vector<std::string> dirs;    // merge: the sweep output directories to join
  std::string plot_format = "png";  // --plot-format png|svg|pdf (the maps)
  std::string keep;                 // --keep envelope: DIR/envelopes.csv.gz (docs/sweep-points.md)
  // the Python module (tools/python): the rig's YAML itself (a dict's), rig_path then only
  // naming it in messages
  std::optional<std::string> rig_text;
};

// The rig text a sweep (or basin) runs: rig_text, else the file's (checked as every command
// checks it, yaml/rig_loader.h), else the built-in rig's.
std::string sweepRigText(const SweepOptions& opt);

struct SweepCommands {
  CLI::App* sweep = nullptr;
  CLI::App* merge = nullptr;
};

// Adds the `sweep` and `merge` subcommands to `app`; their options land in `opt`.
SweepCommands addSweepCommands(CLI::App& app, SweepOptions& opt);

// Each returns the exit code (SPEC 5); a bad rig or command line throws RigError or UsageError
// (exit 2) before anything is written.
int sweepCommand(const SweepOptions& opt);
int mergeCommand(const SweepOptions& opt);

// The sweep's point runner for other commands (basin): the rig text with opt.sets, then `point`
// (KEY=VALUE, a wildcard key set at each of the n metronomes), run with opt's model and engine,
// labelled as a grid point numbered `index`. checkSweepPoint loads it only: throws RigError or
// UsageError (exit 2) naming `where`, else returns {model, engine} names. runSweepPointAt
// records a point that cannot be loaded as failed; nullopt: interrupted by a signal.
std::pair<std::string, std::string> checkSweepPoint(const std::string& rig_text,
                                                    const SweepOptions& opt,
                                                    const std::vector<std::string>& point, int n,
                                                    const std::string& where);
std::optional<SweepPoint> runSweepPointAt(const std::string& rig_text, const SweepOptions& opt,
                                          const std::vector<std::string>& point, int n, long index);

// ---- for other ways of running the points (MPI: tools/cli/sweep_mpi.h) -------------------------

// How one grid point runs: its row, or nullopt when a stop request interrupted it.
using SweepPointRunner = std::function<std::optional<SweepPoint>(long)>;
using SweepPointSink = std::function<void(const SweepPoint&)>;
// The run stage's scheduler, runSweepPoints's contract (sim/analysis/sweep.h): run every g <
// size with wanted(g), hand each result to `finished` (never two at once), stop starting points
// once stop() is true, rethrow the first exception; return how many threads of this process ran
// points (fewer than `jobs` when there are fewer points, or the system refused more threads).
using SweepScheduler = std::function<int(
    long size, const std::function<bool(long)>& wanted, int jobs, const SweepPointRunner& run,
    const SweepPointSink& finished, const std::function<bool()>& stop)>;

// The sweep with its points run by `schedule` (on `ranks` processes, for the summary and
// sweep.json); everything else (checks, --resume, files, maps) as sweepCommand(opt).
int sweepCommand(const SweepOptions& opt, const SweepScheduler& schedule, int ranks);

// A process that only runs points for another one: checks `opt` as the sweep does (RigError or
// UsageError, nothing written) and returns how grid point g runs.
SweepPointRunner sweepPointRunner(const SweepOptions& opt);

}  // namespace metrosync::cli
