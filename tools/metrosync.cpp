// metrosync: the command line (SPEC section 2). Every sub-command is registered with its handler
// (tools/cli/every_command.h: only the one the command line names, when it names one;
// tools/cli/command_line.h maps outcomes to the SPEC section 5 exit codes).
#include <string>

#include "tools/cli/command_line.h"
#include "tools/cli/every_command.h"
#include "tools/cli/mpi_forward.h"
#include "tools/cli/phase_clock.h"

int main(int argc, char** argv) {
  namespace cli = metrosync::cli;
  cli::markPhase("main");  // METROSYNC_PHASES=1: where the program's own code begins
  // `mpirun -np P metrosync sweep ...`: the ranks' sweep is metrosync-mpi's (docs/cluster.md)
  if (argc > 1 && std::string(argv[1]) == "sweep" && cli::mpiRanksFromEnvironment() > 1)
    return cli::forwardToMetrosyncMpi(argc, argv);
  CLI::App app;
  cli::configureApp(app);
  cli::EveryCommand every;
  const std::vector<cli::Command> commands = every.add(app, argc, argv);
  return cli::runCommandLine(app, commands, argc, argv);
}
