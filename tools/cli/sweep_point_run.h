// One point of a sweep (tools/cli/sweep.h) and of a basin: its rig (the base rig, --set, the
// point's values), checked as `run` checks a rig, and its run down to one regimes.csv row.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "models/network.h"
#include "models/rig.h"
#include "models/scaling.h"
#include "sim/analysis/sweep.h"
#include "sim/engines/engine.h"
#include "tools/cli/sweep_options.h"

namespace metrosync::cli {

// How messages name the rig (its text: sweepRigText, tools/cli/sweep_options.h).
std::string displayName(const SweepOptions& opt);

// One grid point, ready to run.
struct PointInput {
  Rig rig;
  ScaledParams scaled;
  const Engine* engine = nullptr;  // the same at every point (no --vary names one)
  std::optional<Network> net;      // a network of platforms (tools/cli/network_sweep.h)
};

// The rig of one point: the base rig, --set, then the point's KEY=VALUE (keys as the user typed
// them: the loader resolves them, docs/keys.md); checked like `run` checks its rig. `where` names
// the point ("grid point 12 (...)"), `source` what set its values; throws RigError naming them.
PointInput loadPointRig(const std::string& text, const SweepOptions& opt,
                        const std::vector<std::string>& point, const std::string& where,
                        const std::string& source = "--vary point");
// ... grid point g.
PointInput loadPoint(const std::string& text, const SweepOptions& opt, const SweepGrid& grid,
                     long g);

// Runs one point: its row, or nullopt when a stop request interrupted it; a failed run is a row
// of regime "failed" with the reason. keep: its envelope rows too (--keep envelope).
std::optional<SweepPoint> runPoint(const PointInput& in, long g, bool keep);
// A point that could not even be loaded: failed, with the loader's message.
SweepPoint unloadablePoint(long g, int n, const std::string& why);

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
