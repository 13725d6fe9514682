// One point of a sweep (tools/cli/sweep.h) and of a basin: its rig (the base rig, --set, the
// point's values), checked as `run` checks a rig; its run is the library's
// (sim/analysis/sweep_point.h).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "models/network.h"
#include "models/rig.h"
#include "models/scaling.h"
#include "sim/analysis/sweep.h"
#include "sim/analysis/sweep_point.h"
#include "sim/engines/engine.h"
#include "tools/cli/sweep_options.h"

namespace metrosync::cli {

// How messages name the rig (its text: sweepRigText, tools/cli/sweep_options.h).
std::string displayName(const SweepOptions& opt);

// One grid point, ready to run: PointInput (sim/analysis/sweep_point.h).

// The rig of one point: the base rig, --set, then the point's KEY=VALUE (keys as the user typed
// them: the loader resolves them, docs/keys.md); checked like `run` checks its rig. `where` names
// the point ("grid point 12 (...)"), `source` what set its values; throws RigError naming them.
PointInput loadPointRig(const std::string& text, const SweepOptions& opt,
                        const std::vector<std::string>& point, const std::string& where,
                        const std::string& source = "--vary point");
// ... grid point g.
PointInput loadPoint(const std::string& text, const SweepOptions& opt, const SweepGrid& grid,
                     long g);

// Runs one point (sim/analysis/sweep_point.h) with the command's hooks: a stop request by a
// signal, the tests' faults. keep: its envelope rows too (--keep envelope).
std::optional<SweepPoint> runPoint(const PointInput& in, long g, bool keep);
// The sweep's point runner for other commands (basin): the rig text with opt.sets, then `point`
// (KEY=VALUE, a wildcard key set at each of the n metronomes), run with opt's model and engine,
// labelled as a grid point numbered `index`. checkSweepPoint loads it only: throws RigError or
// UsageError (exit 2) naming `where`, else returns {model, engine} names. runSweepPointAt
// records a point that cannot be loaded as failed; nullopt: interrupted by a signal.
std::pair<std::string, std::string> checkSweepPoint(const std::string& rig_text,
                                                    const SweepOptions& opt,
                                                    const std::vector<std::string>& point, int n,
                                                    const std::string& where);
std::optional<SweepPoint> runSweepPointAt(const std::string& rig_text, const SweepOptions& opt,
                                          const std::vector<std::string>& point, int n, long index);

}  // namespace metrosync::cli
