#include "tools/cli/mpi_forward.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "tools/cli/commands.h"

namespace metrosync::cli {

namespace {

int envInt(const char* name) {
  const char* v = std::getenv(name);
  return v && *v ? std::atoi(v) : 0;
}

}  // namespace

int mpiRanksFromEnvironment() {
  int n = std::max(envInt("OMPI_COMM_WORLD_SIZE"), envInt("PMI_SIZE"));
  if (std::getenv("PMIX_RANK")) n = std::max(n, envInt("SLURM_STEP_NUM_TASKS"));
  return std::max(1, n);
}

int forwardToMetrosyncMpi(int argc, char** argv) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::string mpi = ec ? std::string() : (self.parent_path() / "metrosync-mpi").string();
  if (!mpi.empty() && ::access(mpi.c_str(), X_OK) == 0) {
    std::vector<char*> args = {const_cast<char*>("metrosync-mpi")};
    for (int k = 1; k < argc; ++k) args.push_back(argv[k]);
    args.push_back(nullptr);
    ::execv(mpi.c_str(), args.data());
  }
  std::cerr << "metrosync: error: started as one of " << mpiRanksFromEnvironment()
            << " MPI ranks, but " << (mpi.empty() ? std::string("metrosync-mpi") : mpi)
            << (errno == ENOENT ? " does not exist" : " cannot be started")
            << ": build it (CMake builds it when it finds MPI: apt-get install libopenmpi-dev "
               "openmpi-bin) and run `mpirun -np P metrosync-mpi sweep ...` (docs/cluster.md)\n";
  return kBadInput;
}

}  // namespace metrosync::cli
