// The plots of a network run (docs/networks.md), from its files' rows
// (tools/report/network_files.h).
#pragma once

#include <string>
#include <vector>

#include "models/network.h"
#include "tools/report/network_files.h"
#include "tools/report/output_dir.h"

namespace metrosync {

// The plots of a network run: order.png (r per platform and overall against tau) and raster.png
// (metronome against tau, colour = phase relative to its platform's mean). Returns the files made
// (none when gnuplot is missing).
std::vector<std::string> plotNetwork(const OutputDir& dir, const NetworkFiles& files,
                                     const Network& net, const std::string& title);

}  // namespace metrosync
