// `metrosync sweep` and `metrosync merge` (SPEC section 2): regime maps over one or two rig keys,
// run in parallel, resumable, in shards that merge joins. The grid, the points and the scheduling
// are sim/analysis/sweep.h, the files tools/report/sweep_files.h, the maps
// tools/report/sweep_maps.h; this is the command line and how one point runs.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace metrosync::cli {

struct SweepOptions {
  std::string rig_path;           // empty: the built-in default rig
  std::vector<std::string> sets;  // --set KEY=VALUE, in order
  std::vector<std::string> vary;  // --vary KEY=FROM:TO:COUNT[:open] or KEY=V1,V2,.. (first: across)
  std::string out;                // --out DIR; empty: runs/<rig name>-sweep (-merge)
  bool quiet = false;
  bool no_plot = false;     // sweep: --no-plot, no maps
  bool boundaries = false;  // sweep: --boundaries, the slow flow's fold and Hopf curves
  std::string model;        // slow | full; empty: the --engine's model, else slow
  std::string engine;       // a registry name (sim/engines/engine.h); empty: the model's default
  int jobs = 0;             // worker threads; 0: the number of cores
  bool resume = false;
  std::string shard;              // "K/N"; empty: the whole grid
  std::string keep;               // --keep envelope: DIR/envelopes.csv.gz (docs/sweep-points.md)
  std::vector<std::string> dirs;  // merge: the sweep output directories to join
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

}  // namespace metrosync::cli
