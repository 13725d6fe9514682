// A sweep's output folder (tools/cli/sweep.h): what an earlier command left there (stale files,
// removed) and what --resume keeps of it.
#pragma once

#include <string>

#include "tools/cli/sweep_plan.h"
#include "tools/report/outputs.h"
#include "tools/report/sweep_files.h"

namespace metrosync::cli {

// Removes the sweep's own files left in `dir` by an earlier command, and the temporary files of
// commands that are no longer running; run's files too.
void removeStaleSweepOutputs(const OutputDir& dir);

// --resume: the same sweep, and what it already has (this shard's rows only); `resuming` says
// whether there was one to resume. Throws UsageError for another sweep's folder.
RegimesTable resumeTable(const SweepOptions& opt, const SweepPlan& plan, bool& resuming);

// --resume --keep envelope: the points of regimes.csv whose envelope rows are not whole in the
// store (a damaged member, and every member after it, is cut) are dropped from `table`: they run
// again, so that the store holds every point it claims (issue 29).
void dropPointsWithoutEnvelopes(RegimesTable& table, const std::string& store_path);

// The folder, made if need be, its stale files removed unless resuming (UsageError: --out).
OutputDir openSweepDir(const std::string& path, bool resuming);

}  // namespace metrosync::cli
