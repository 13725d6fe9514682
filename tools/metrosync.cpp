// metrosync: the command line (SPEC section 2). Every sub-command is registered with its handler
// (tools/cli/command_line.h maps outcomes to the SPEC section 5 exit codes).
#include <string>

#include "tools/cli/animate.h"
#include "tools/cli/basin.h"
#include "tools/cli/command_line.h"
#include "tools/cli/continue.h"
#include "tools/cli/figures.h"
#include "tools/cli/fit.h"
#include "tools/cli/mpi_forward.h"
#include "tools/cli/phase_clock.h"
#include "tools/cli/sweep.h"
#include "tools/cli/sweep_point.h"
#include "tools/cli/validate.h"

int main(int argc, char** argv) {
  namespace cli = metrosync::cli;
  cli::markPhase("main");  // METROSYNC_PHASES=1: where the program's own code begins
  // `mpirun -np P metrosync sweep ...`: the ranks' sweep is metrosync-mpi's (docs/cluster.md)
  if (argc > 1 && std::string(argv[1]) == "sweep" && cli::mpiRanksFromEnvironment() > 1)
    return cli::forwardToMetrosyncMpi(argc, argv);
  CLI::App app;
  cli::configureApp(app);
  cli::Options opt;                   // run, compare, scale (tools/cli/commands.h)
  cli::SweepOptions sweep_opt;        // sweep and merge (tools/cli/sweep.h)
  cli::ValidateOptions validate_opt;  // tools/cli/validate.h
  cli::FitOptions fit_opt;            // tools/cli/fit.h
  cli::MeasureOptions measure_opt;
  cli::FiguresOptions figures_opt;   // tools/cli/figures.h
  cli::AnimateOptions animate_opt;   // tools/cli/animate.h
  cli::BasinOptions basin_opt;       // tools/cli/basin.h
  cli::SweepPointOptions point_opt;  // tools/cli/sweep_point.h
  std::vector<cli::Command> commands = cli::addRigCommands(app, opt);
  const cli::SweepCommands sweep = cli::addSweepCommands(app, sweep_opt);
  commands.push_back({sweep.sweep, [&] { return cli::sweepCommand(sweep_opt); }});
  commands.push_back({sweep.merge, [&] { return cli::mergeCommand(sweep_opt); }});
  commands.push_back({cli::addValidateCommand(app, validate_opt),
                      [&] { return cli::validateCommand(validate_opt); }});
  commands.push_back({cli::addContinueCommand(app), [] { return cli::continueCommand(); }});
  commands.push_back({cli::addFitCommand(app, fit_opt), [&] { return cli::fitCommand(fit_opt); }});
  commands.push_back(
      {cli::addMeasureCommand(app, measure_opt), [&] { return cli::measureCommand(measure_opt); }});
  commands.push_back(
      {cli::addFiguresCommand(app, figures_opt), [&] { return cli::figuresCommand(figures_opt); }});
  commands.push_back(
      {cli::addAnimateCommand(app, animate_opt), [&] { return cli::animateCommand(animate_opt); }});
  commands.push_back(
      {cli::addBasinCommand(app, basin_opt), [&] { return cli::basinCommand(basin_opt); }});
  commands.push_back({cli::addSweepPointCommand(app, point_opt),
                      [&] { return cli::sweepPointCommand(point_opt); }});
  return cli::runCommandLine(app, commands, argc, argv);
}
