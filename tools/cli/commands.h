// The commands of `metrosync` (SPEC section 2) behind the command-line parser: each takes its
// parsed options and returns the process exit code (SPEC section 5).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "tools/report/run_columns.h"
#include "yaml/rig_limits.h"

namespace metrosync::cli {

enum ExitCode : int { kSuccess = 0, kOtherError = 1, kBadInput = 2, kSimulationFailed = 3 };

// A bad command line found after parsing (exit 2); what() is printed after "metrosync: error: ".
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Options {
  std::string rig_path;           // empty: the built-in default rig
  std::vector<std::string> sets;  // --set KEY=VALUE, in order
  std::string out;                // --out DIR; empty: runs/<rig name>-<command>
  bool quiet = false;
  bool no_plot = false;  // run, compare: --no-plot, no PNG (and no gnuplot child process)
  std::string plot_format = "png";  // run, compare: --plot-format png|svg|pdf
  std::string model;   // run: full | slow; empty: the engine's model, full when no --engine
  std::string engine;  // run, compare: a registry name (sim/engines/engine.h); empty: default
  bool json = false;   // scale
  double max_output = kDefaultMaxOutputBytes;  // --max-output BYTES (yaml/rig_limits.h)
  // The Python module (tools/python): the rig's YAML itself (a dict's), rig_path then only
  // naming it in messages; and run, compare without a folder (no_files): nothing is written, the
  // rows go only to the taps below and the summary is returned.
  std::optional<std::string> rig_text;
  bool no_files = false;
};

// Each returns the exit code; a bad rig or command line throws RigError or UsageError (exit 2),
// before anything is written.
int runCommand(const Options& opt);
int compareCommand(const Options& opt);
int scaleCommand(const Options& opt);
// run and compare for the Python module: the exit code (0, or 3 when a simulation failed),
// summary.json's object ("files" empty without a folder) and the rows kept in memory, beside the
// files or (Options::no_files) instead of them.
struct RunOutcome {
  int code = kSuccess;
  nlohmann::json summary;
  std::optional<RunColumns> rows;       // run: its model's; compare: the full model's
  std::optional<RunColumns> slow_rows;  // compare: the slow flow's
  // compare: comparison.csv's columns, from the rows in memory; without a folder the summary's
  // comparison is computed from them too (with one, from the files, as the CLI's)
  ColumnTable comparison;
};
RunOutcome runKeepingRows(const Options& opt);
RunOutcome compareKeepingRows(const Options& opt);

// What `scale --json` prints, as text (the Python module's Rig.scaled()).
std::string scaledJsonText(const Options& opt);

// Installs SIGINT/SIGTERM handlers that ask the running simulation to stop (files are kept and
// marked incomplete); a second signal kills the process as usual.
void installStopHandlers();

}  // namespace metrosync::cli
