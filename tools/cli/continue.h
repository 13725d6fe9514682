// `metrosync continue` (issue 12): the slow flow's locked states followed in one rig key, with
// their stability and bifurcations (sim/analysis/continuation/, files tools/report/
// continuation_report.h).
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "models/rig.h"
#include "sim/analysis/continuation/fold_curve.h"
#include "sim/analysis/continuation/result.h"

namespace metrosync::cli {

struct ContinueOptions {
  std::string rig_path;           // empty: the built-in default rig
  std::string model = "slow";     // --model slow|full (full: tools/cli/continue_full.h)
  std::vector<std::string> sets;  // --set KEY=VALUE, in order
  std::string param;              // --param KEY
  double to = 0.0;                // --to VALUE
  std::optional<double> from;     // --from VALUE; default: the rig's value of KEY
  std::string start;              // --start A_1,..,A_N,psi_2,..,psi_N
  double step = 0.0;              // --step H (arclength); 0: |to - from| / 100
  int max_points = 500;           // per direction of each branch
  bool all = false;               // --all: every locked state at the start value
  std::string out;                // --out DIR; empty: runs/<rig name>-continue
  bool quiet = false;
  bool no_cycles = false;  // --no-cycles
  int cycle_points = 100;  // --cycle-points: each limit cycle's point budget
  std::string fold_key;    // --fold KEY2: continue each fold in KEY and KEY2
  double to2 = 0.0;        // --to2 VALUE: KEY2's other end (it starts at the rig's value)
};

// Adds the `continue` subcommand; its options land in a static ContinueOptions.
CLI::App* addContinueCommand(CLI::App& app);

// The exit code (SPEC 5); bad input throws RigError or UsageError (exit 2) before anything is
// written.
int continueCommand();

// The fold and Hopf curves of the slow flow in (key1, key2) over [lo1, hi1] x [lo2, hi2]: the
// computed boundaries of a slow sweep map (`sweep --boundaries`). At three rows of key2 (1/6, 1/2
// and 5/6 of its range) every locked state Newton finds at key1 = lo1 (as `continue --all`) is
// followed in key1; every fold and Hopf point found is followed in key2 across its range, unless
// a curve already found passes through it. Throws UsageError for a key the slow flow ignores.
// The checks of boundaryCurves alone (before a sweep writes anything): UsageError for a key that
// does not change the slow flow or a range of zero width.
void checkBoundaryKeys(const std::string& rig_path, const std::vector<std::string>& sets,
                       const std::string& key1, double lo1, double hi1, const std::string& key2,
                       double lo2, double hi2);
std::vector<continuation::FoldCurve> boundaryCurves(const std::string& rig_path,
                                                    const std::vector<std::string>& sets,
                                                    const std::string& key1, double lo1, double hi1,
                                                    const std::string& key2, double lo2,
                                                    double hi2);
// The same with the options given.
int continueCommand(const ContinueOptions& opt);

// The rig with --set, then `extra` (the parameter's KEY=VALUE, named --param in messages; keys
// as in docs/keys.md: metronomes.*.X sets X of every metronome). Throws RigError.
Rig loadContinueRig(const ContinueOptions& opt, const std::vector<std::string>& extra);
// The slow flow's continuation as values, nothing written (the Python module's continue_; one
// function per model: `--model full` dispatches to its own). Bad input throws RigError or
// UsageError.
continuation::ContinuationResult slowFlowContinuation(const ContinueOptions& opt);

}  // namespace metrosync::cli
