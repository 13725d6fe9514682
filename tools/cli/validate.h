// `metrosync validate [--out DIR] [--quick] [--engine E]`: the full model against the asymptotics
// (the slow flow and its closed forms), written up as DIR/report.md with its plots
// (sim/analysis/validation/validation.h, tools/report/validation_report.h). Registered in
// tools/cli/every_command.cpp.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "sim/analysis/validation/validation.h"

namespace metrosync::cli {

struct ValidateOptions {
  std::string out = "runs/validate";  // --out DIR
  bool quick = false;                 // --quick: the reduced plan
  std::string rigs;                   // --rigs DIR; empty: found (see validate.cpp)
  int jobs = 0;                       // --jobs N; 0 (not given): one per hardware thread
  bool quiet = false;
  std::string engine = "direct";  // --engine: the full model's engine
};

// Adds the `validate` subcommand to `app`, parsing into `opt`.
CLI::App* addValidateCommand(CLI::App& app, ValidateOptions& opt);

// Runs it: exit 0 when every check passes, 1 when a check fails (the report says which), 3 when a
// simulation stopped early (the report is still written), 2 for a bad command line.
int validateCommand(const ValidateOptions& opt);

// The shipped rigs' directory: `given`, else yaml/rigs under the working directory, else above
// the executable, else its installation's share/metrosync/rigs. Throws UsageError.
std::string findRigsDir(const std::string& given);

// The shipped scenarios (shippedScenarios()) loaded from `rigs_dir` and scaled; a bad rig throws
// RigError naming its file.
std::vector<Scenario> loadScenarios(const std::string& rigs_dir);

}  // namespace metrosync::cli
