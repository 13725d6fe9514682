// `metrosync sweep-point DIR INDEX`: one grid point of a sweep, re-run with the full outputs of
// `run` (envelope.csv, trajectory.csv for the full model, envelope.png, summary.json) into
// DIR/point-INDEX/ (or --out). The point's rig is the sweep's: the rig text recorded in
// DIR/sweep.json, its --set, then the point's --vary values, with the sweep's model and engine
// (docs/sweep-points.md).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace metrosync::cli {

struct SweepPointOptions {
  std::string dir;  // a sweep's --out
  long index = -1;  // the grid index (regimes.csv's `index` column)
  std::string out;  // empty: DIR/point-INDEX
  bool quiet = false;
  bool no_plot = false;
};

CLI::App* addSweepPointCommand(CLI::App& app, SweepPointOptions& opt);

// The exit code of `run` on the point; a missing or foreign DIR, or an INDEX outside the grid,
// throws UsageError (exit 2) before anything is written.
int sweepPointCommand(const SweepPointOptions& opt);

}  // namespace metrosync::cli
