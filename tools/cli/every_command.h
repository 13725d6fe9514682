// Every sub-command of `metrosync`, in groups that share their options (run, compare and scale;
// sweep and merge; each other command alone), registered on demand: CLI11 builds each option's
// help text and validators as it is added, and the whole tree costs about 0.4 ms of a short
// run's process (docs/bench/speed/process.md, "args"). A command line whose first word names a
// command builds that command's group only; any other (no command, --help, --version, a
// misspelt command) builds every group, in the order `metrosync --help` lists them.
// tests/cli/test_every_command.cpp holds that a group alone parses, helps and refuses exactly as
// in the whole tree.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "tools/cli/animate.h"
#include "tools/cli/basin.h"
#include "tools/cli/command_line.h"
#include "tools/cli/commands.h"
#include "tools/cli/figures.h"
#include "tools/cli/fit.h"
#include "tools/cli/sweep.h"
#include "tools/cli/sweep_point.h"
#include "tools/cli/validate.h"

namespace metrosync::cli {

class EveryCommand {
 public:
  // The groups' command names, in registration order (a group registers exactly its names).
  static const std::vector<std::vector<std::string>>& groups();

  // What argv needs: the group its first word names, else every group.
  std::vector<Command> add(CLI::App& app, int argc, char** argv);
  std::vector<Command> addAll(CLI::App& app);
  std::vector<Command> addGroup(CLI::App& app, size_t group);

 private:
  Options opt_;               // run, compare, scale (tools/cli/commands.h)
  SweepOptions sweep_;        // sweep and merge (tools/cli/sweep.h)
  ValidateOptions validate_;  // tools/cli/validate.h
  FitOptions fit_;            // tools/cli/fit.h
  MeasureOptions measure_;    //
  FiguresOptions figures_;    // tools/cli/figures.h
  AnimateOptions animate_;    // tools/cli/animate.h
  BasinOptions basin_;        // tools/cli/basin.h
  SweepPointOptions point_;   // tools/cli/sweep_point.h
};

}  // namespace metrosync::cli
