// metrosync-mpi: `metrosync sweep` and `metrosync basin` over MPI processes (docs/cluster.md,
// tools/cli/sweep_mpi.h):
//   mpirun -np P metrosync-mpi sweep RIG --vary ... [--jobs J] [--resume] --out DIR
//   mpirun -np P metrosync-mpi basin RIG --random ... --samples S [--seed N] --out DIR
// A separate executable, so that `metrosync` itself, the Python module and the Debian package do
// not load libmpi (whose initialisation outside mpirun/srun is slow or fails on some systems).
// Rank 0 prints and writes everything; the other ranks stay silent unless something goes wrong
// on their node.
#include <mpi.h>
#include <unistd.h>

#include <cstdio>
#include <optional>

#include "tools/cli/command_line.h"
#include "tools/cli/sweep.h"
#include "tools/cli/sweep_mpi.h"

namespace {

// A worker rank parses the same command line as rank 0: its --help and parse errors would only
// repeat rank 0's, so stdout and stderr go to /dev/null until its handler runs.
struct Silenced {
  Silenced() {
    std::fflush(nullptr);
    out = ::dup(1);
    err = ::dup(2);
    if (FILE* null = std::fopen("/dev/null", "w")) {
      ::dup2(::fileno(null), 1);
      ::dup2(::fileno(null), 2);
      std::fclose(null);
    }
  }
  void restore() {
    if (out < 0) return;
    std::fflush(nullptr);
    ::dup2(out, 1);
    ::dup2(err, 2);
    ::close(out);
    ::close(err);
    out = err = -1;
  }
  int out = -1, err = -1;
};

}  // namespace

int main(int argc, char** argv) {
  namespace cli = metrosync::cli;
  int provided = 0, rank = 0, ranks = 1;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  CLI::App app;
  cli::configureApp(app);
  app.name("metrosync-mpi");
  app.description(
      "metrosync sweep and basin over MPI processes: mpirun -np P metrosync-mpi sweep|basin ... "
      "(docs/cluster.md)");
  cli::SweepOptions opt;
  const cli::SweepCommands sweep = cli::addSweepCommands(app, opt);
  app.remove_subcommand(sweep.merge);  // merge needs no MPI: `metrosync merge`
  cli::BasinOptions basin_opt;
  CLI::App* basin = cli::addBasinCommand(app, basin_opt);
  std::optional<Silenced> silenced;
  if (rank > 0) silenced.emplace();
  const std::vector<cli::Command> commands = {{sweep.sweep,
                                               [&] {
                                                 if (rank == 0)
                                                   return cli::mpiSweepCoordinator(opt, ranks);
                                                 silenced->restore();
                                                 return cli::mpiSweepWorker(opt);
                                               }},
                                              {basin, [&] {
                                                 if (rank == 0)
                                                   return cli::mpiBasinCoordinator(basin_opt,
                                                                                   ranks);
                                                 silenced->restore();
                                                 return cli::mpiBasinWorker(basin_opt);
                                               }}};
  const int code = cli::runCommandLine(app, commands, argc, argv);
  if (silenced) silenced->restore();
  MPI_Finalize();
  return code;
}
