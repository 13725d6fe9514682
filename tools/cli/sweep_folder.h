// A sweep's output folder (tools/cli/sweep.h): what an earlier command left there (stale files,
// removed) and what --resume keeps of it.
#pragma once

#include <set>
#include <string>

#include "tools/cli/sweep_plan.h"
#include "tools/report/outputs.h"
#include "tools/report/sweep_files.h"

namespace metrosync::cli {

// Removes the sweep's own files left in `dir` by an earlier command, and the temporary files of
// commands that are no longer running; run's files too.
void removeStaleSweepOutputs(const OutputDir& dir);

// --resume: does plan.path hold this sweep to resume (false: nothing to resume, said unless
// quiet)? Throws UsageError for another sweep's folder, or a regimes.csv without sweep.json.
bool checkResumable(const SweepOptions& opt, const SweepPlan& plan);

// --resume --keep envelope: the points whose envelope rows are whole in the store (a damaged
// member, and every member after it, is cut); the others run again, so that the store holds every
// point it claims (issue 29).
std::set<long> storedEnvelopePoints(const std::string& store_path);

// The folder, made if need be, its stale files removed unless resuming (UsageError: --out).
OutputDir openSweepDir(const std::string& path, bool resuming);

}  // namespace metrosync::cli
