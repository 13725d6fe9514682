// The plots of a network run (docs/networks.md), from its files' rows
// (tools/report/network_files.h).
#pragma once

#include <string>
#include <vector>

#include "models/network.h"
#include "tools/report/network_files.h"
#include "tools/report/output_dir.h"
#include "tools/report/plot.h"

namespace metrosync {

// The plots' time axis: a network is physical, so seconds with tau on the top axis, from 0 to
// the last sample (the axis ends with the data).
struct NetworkPlotAxes {
  PlotStyle style;
  double tau_end = 0.0;
};
NetworkPlotAxes networkPlotAxes(const Network& net, const NetworkFiles& files);

// The gnuplot scripts of order.png and raster.png (exposed for tests).
std::string networkOrderScript(const Network& net, const NetworkPlotAxes& axes,
                               const std::string& title, const std::string& data,
                               const std::string& png);
std::string networkRasterScript(const Network& net, const NetworkPlotAxes& axes,
                                const std::string& title, const std::string& data,
                                const std::string& png);

// The plots of a network run: order.png (r per platform and overall against time) and raster.png
// (metronome against time, colour = phase relative to its platform's mean), .svg or .pdf in
// those formats (--plot-format: tools/report/plot.h, plotTerminal, as a single rig's plots).
// Returns the files made (none when gnuplot is missing).
std::vector<std::string> plotNetwork(const OutputDir& dir, const NetworkFiles& files,
                                     const Network& net, const std::string& title,
                                     const std::string& format = "png");

}  // namespace metrosync
