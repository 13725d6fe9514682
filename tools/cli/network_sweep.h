// `metrosync sweep` on a network of platforms (docs/networks.md): the network as the sweep's rig
// (the grid, the files and the maps are the sweep's own, tools/cli/sweep.h; a point runs through
// the sweep's one point runner for a rig and a network, runPoint in tools/cli/sweep_point_run.h).
// A point's row in regimes.csv: regime = the network's label (synchronized, chimera,
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

namespace metrosync::cli {

// The network as one Rig for the sweep's bookkeeping: its name and simulation settings, and all
// its metronomes in the network's numbering (the point's metronome count is checked on it).
Rig networkSweepRig(const Network& net);

// The swept rig of sweep, basin and the Python module, its text parsed once: a single rig (a
// single-platform text, or a network of one: Network::isSingleRig) as loadRigText gives it, a
// network of several as networkSweepRig, that network itself in `net` when given. Throws
// RigError as the loaders do.
Rig loadSweepRig(const std::string& text, const std::string& name,
                 const std::vector<std::string>& sets, std::optional<Network>* net = nullptr);

}  // namespace metrosync::cli
