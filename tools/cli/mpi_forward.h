// `mpirun -np P metrosync sweep ...`: started as one of several MPI ranks, `metrosync` (which
// never loads libmpi) replaces itself with `metrosync-mpi` from its own directory, same pid, same
// environment, same arguments, so that the ranks form one sweep (docs/cluster.md).
#pragma once

namespace metrosync::cli {

// How many ranks the launcher started, from its environment (OpenMPI's mpirun:
// OMPI_COMM_WORLD_SIZE; MPICH/Slurm PMI: PMI_SIZE; Slurm PMIx: SLURM_STEP_NUM_TASKS with
// PMIX_RANK); 1 when not started by an MPI launcher.
int mpiRanksFromEnvironment();

// Execs metrosync-mpi (next to /proc/self/exe) with argv[1..]; returns only when that is
// impossible, with exit code 2 and a message saying what to run instead.
int forwardToMetrosyncMpi(int argc, char** argv);

}  // namespace metrosync::cli
