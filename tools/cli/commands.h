// The commands of `metrosync` (SPEC section 2) behind the command-line parser: each takes its
// parsed options and returns the process exit code (SPEC section 5).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>

#include "tools/cli/exit_codes.h"
#include "tools/cli/run_options.h"
#include "tools/cli/stop_signals.h"
#include "tools/report/run_columns.h"

namespace metrosync::cli {

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

}  // namespace metrosync::cli
