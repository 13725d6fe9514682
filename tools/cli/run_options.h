// The options of run, compare and scale (tools/cli/commands.h), as the command line or the
// Python module gives them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "yaml/rig_limits.h"

namespace metrosync::cli {

struct Options {
  std::string rig_path;           // empty: the built-in default rig
  std::vector<std::string> sets;  // --set KEY=VALUE, in order
  std::string out;                // --out DIR; empty: runs/<rig name>-<command>
  bool quiet = false;
  bool no_plot = false;  // run, compare: --no-plot, no PNG (and no gnuplot child process)
  std::string plot_format = "png";  // run, compare: --plot-format png|svg|pdf
  std::string model;    // run: full | slow; empty: the engine's model, full when no --engine
  std::string engine;   // run, compare: a registry name (sim/engines/engine.h); empty: default
  bool json = false;    // scale
  bool strict = false;  // --strict: a value outside its sensible range is an error (exit 2)
  double max_output = kDefaultMaxOutputBytes;  // --max-output BYTES (yaml/rig_limits.h)
  // The Python module (tools/python): the rig's YAML itself (a dict's), rig_path then only
  // naming it in messages; and run, compare without a folder (no_files): nothing is written, the
  // rows go only to the taps below and the summary is returned.
  std::optional<std::string> rig_text;
  bool no_files = false;
};

}  // namespace metrosync::cli
