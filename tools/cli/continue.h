// `metrosync continue` (issue 12): the slow flow's locked states followed in one rig key, with
// their stability and bifurcations (sim/analysis/continuation/, files tools/report/
// continuation_report.h).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "sim/analysis/continuation/fold_curve.h"
#include "sim/analysis/continuation/result.h"
#include "tools/cli/continue_options.h"

namespace metrosync::cli {

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

// The slow flow's continuation as values, nothing written (the Python module's continue_; one
// function per model: `--model full` dispatches to its own). Bad input throws RigError or
// UsageError.
continuation::ContinuationResult slowFlowContinuation(const ContinueOptions& opt);

}  // namespace metrosync::cli
