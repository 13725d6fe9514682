// `metrosync sweep` and `metrosync merge` (SPEC section 2): regime maps over one or two rig keys,
// run in parallel, resumable, in shards that merge joins. The grid, the points and the scheduling
// are sim/analysis/sweep.h, the files tools/report/sweep_files.h, the maps
// tools/report/sweep_maps.h; this is the command line and how one point runs.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
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
};

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

}  // namespace metrosync::cli
