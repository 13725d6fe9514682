// The commands of `metrosync` (SPEC section 2) behind the command-line parser: each takes its
// parsed options and returns the process exit code (SPEC section 5).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

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
};

// Each returns the exit code; a bad rig or command line throws RigError or UsageError (exit 2),
// before anything is written.
int runCommand(const Options& opt);
int compareCommand(const Options& opt);
int scaleCommand(const Options& opt);
// What `scale --json` prints, as text (the Python module's Rig.scaled()).
std::string scaledJsonText(const Options& opt);

// Installs SIGINT/SIGTERM handlers that ask the running simulation to stop (files are kept and
// marked incomplete); a second signal kills the process as usual.
void installStopHandlers();

}  // namespace metrosync::cli
