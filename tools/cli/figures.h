// `metrosync figures [--out DIR] [--model slow|full|both] [--only ID]... [--quick]`: the paper's
// section-4 figures (f4.1-f4.4) and the computed regime diagram (exp1), PNG and SVG, with an
// index figures.md. Which runs: sim/analysis/figures/paper_figures.h; the map: a `metrosync sweep`;
// the files: tools/report/figures.h. Registered in tools/cli/every_command.cpp.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace metrosync::cli {

struct FiguresOptions {
  std::string out = "runs/figures";  // --out DIR
  std::string model = "slow";        // slow | full | both
  std::vector<std::string> only;     // --only ID: f4.1 .. f4.4, exp1; empty: all
  bool quick = false;                // --quick: a 12 x 12 regime map instead of 40 x 40
  std::string rigs;                  // --rigs DIR; empty: found as validate finds them
  int jobs = 0;                      // --jobs N; 0 (not given): one per hardware thread
  std::string engine = "direct";     // the full model's engine
  bool quiet = false;
};

CLI::App* addFiguresCommand(CLI::App& app, FiguresOptions& opt);

// 0 success; 2 bad command line or rig (nothing written); 3 a run failed or was interrupted (the
// figures are still written).
int figuresCommand(const FiguresOptions& opt);

}  // namespace metrosync::cli
