// The command line of `metrosync` (SPEC section 2): every sub-command registered on one CLI11 app
// with its handler, and the one place that maps what a command throws to the SPEC section 5 exit
// codes (0 success, 2 bad command line or rig, nothing written; 3 the simulation failed; 1
// anything else). tools/cli/every_command.h builds the list (the commands argv names);
// tools/metrosync.cpp calls runCommandLine().
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <vector>

#include "tools/cli/commands.h"

namespace metrosync::cli {

// A registered sub-command and what runs when it was the one parsed.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> handler;
};

// The top-level app: name, description, --version, exactly one sub-command, the exit codes.
void configureApp(CLI::App& app);

// run, compare and scale, sharing `opt`.
std::vector<Command> addRigCommands(CLI::App& app, Options& opt);

// Parses argv and runs the parsed command; returns the exit code (parse errors: 2, --help and
// --version: 0).
int runCommandLine(CLI::App& app, const std::vector<Command>& commands, int argc, char** argv);

}  // namespace metrosync::cli
