// `metrosync basin RIG --random KEY=FROM:TO [--random ...] --samples S [--seed N] [--jobs J]
// [--model slow|full] [--out DIR]` (docs/basin.md): basin stability, the fraction of random starts
// that end in each regime, with 95% Wilson intervals. Each sample runs as a sweep point
// (tools/cli/sweep.h: the same runner and regime labels); the draws are sim/analysis/basin.h, the
// files tools/report/basin_files.h.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "tools/cli/sweep.h"

namespace metrosync::cli {

struct BasinOptions {
  SweepOptions run;                 // RIG, --set, --model, --engine, --jobs, --out, --quiet
  std::vector<std::string> random;  // --random KEY=FROM:TO, in order
  long samples = 0;                 // --samples S
  std::uint64_t seed = 1;           // --seed N
  bool no_plot = false;             // --no-plot
};

CLI::App* addBasinCommand(CLI::App& app, BasinOptions& opt);

// Bad options or rig: UsageError / RigError (exit 2) before anything is written; interrupted by
// a signal: exit 3 with nothing written. Failed runs are counted as the regime `failed`.
int basinCommand(const BasinOptions& opt);

// The command with its samples run by `schedule` (MPI: tools/cli/sweep_mpi.h) on `ranks`
// processes; everything else as basinCommand(opt).
int basinCommand(const BasinOptions& opt, const SweepScheduler& schedule, int ranks);

// A process that only runs samples for another one: checks `opt` as basin does and returns how
// sample k runs.
SweepPointRunner basinSampleRunner(const BasinOptions& opt);

}  // namespace metrosync::cli
