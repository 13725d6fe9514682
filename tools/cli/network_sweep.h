// `metrosync sweep` on a network of platforms (docs/networks.md): how one grid point of a network
// loads and runs (the grid, the files and the maps are the sweep's own, tools/cli/sweep.h). A
// point's row in regimes.csv: regime = the network's label (synchronized, chimera,
// antiphase-groups, disordered), A_1..A_N and psi_2..psi_N final in the network's numbering and
// scales (as its envelope.csv), r = the final Kuramoto order parameter over the whole network (as
// summary.json's network.r), s empty, clusters = each platform's regime ("left=in-phase|right=
// drifting"). A network of one platform on the table, uncoupled, is today's rig and never comes
// here.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "models/network.h"
#include "sim/analysis/sweep.h"
#include "sim/engines/engine.h"

namespace metrosync::cli {

// The network as one Rig for the sweep's bookkeeping: its name and simulation settings, and all
// its metronomes in the network's numbering (the point's metronome count is checked on it).
Rig networkSweepRig(const Network& net);

// Runs one grid point (never throws for a failed simulation: regime "failed" and the reason).
// `inject_failure`: the point fails for this reason as a simulation failure would (a test's
// fault hook, tools/cli/fault_hooks.h).
SweepPoint runNetworkSweepPoint(const Network& net, const Engine& engine, long g,
                                const std::optional<std::string>& inject_failure = std::nullopt);

}  // namespace metrosync::cli
