// solveLocal (least_squares.h) is Ceres Solver's, and Ceres brings glog, SuiteSparse,
// METIS, OpenMP and LAPACK in: its implementation (ceres_solve.cpp) is the plugin
// metrosync-ceres.so, which `metrosync` loads when fit or measure runs (sim/engines/
// plugin_loader.h, docs/bench/process.md); the tests and the Python module link it directly.
#pragma once

#include "sim/analysis/fit/local_problem.h"

namespace metrosync {

inline constexpr const char* kCeresPluginFile = "metrosync-ceres.so";
constexpr int kCeresPluginAbi = 3;  // raised whenever the table changes

struct CeresPlugin {
  int abi = kCeresPluginAbi;
  LocalSolution (*solve)(const LocalProblem&) = nullptr;  // ceres_solve.cpp's Ceres solve
};

// The table, loading the plugin on the first call (thread-safe); throws PluginError when it
// cannot. The commands call it before writing anything.
const CeresPlugin& ceresPlugin();

// ceres_solve.cpp's implementation, which solveLocal (least_squares.cpp) calls through the table.
LocalSolution solveLocalWithCeres(const LocalProblem& problem);

}  // namespace metrosync

// The plugin's one entry point.
extern "C" const metrosync::CeresPlugin* metrosync_ceres_plugin();
