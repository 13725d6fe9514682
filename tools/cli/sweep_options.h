// sweep's and merge's options (tools/cli/sweep.h) and their command lines (sweep_options.cpp).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

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
  bool strict = false;              // --strict: sensible ranges (docs/sensible-ranges.md)
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

}  // namespace metrosync::cli
