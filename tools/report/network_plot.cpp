#include "tools/report/network_plot.h"

#include <sstream>

#include "base/number_text.h"
#include "models/scaling.h"
#include "tools/report/plot.h"

namespace metrosync {

namespace {

std::string rowsText(const std::vector<std::vector<double>>& rows) {
  std::ostringstream os;
  for (const auto& r : rows) {
    for (std::size_t k = 0; k < r.size(); ++k) os << (k ? " " : "") << numberText(r[k], 9);
    os << "\n";
  }
  return os.str();
}

// one "tau metronome phase" line per metronome and kept sample, for a palette raster
std::string rasterText(const std::vector<std::vector<double>>& rows) {
  std::ostringstream os;
  for (const auto& r : rows)
    for (std::size_t k = 1; k < r.size(); ++k)
      os << numberText(r[0]) << " " << k << " " << numberText(r[k]) << "\n";
  return os.str();
}

double lastTau(const std::vector<std::vector<double>>& rows) {
  return rows.empty() || rows.back().empty() ? 0.0 : rows.back()[0];
}

}  // namespace

NetworkPlotAxes networkPlotAxes(const Network& net, const NetworkFiles& files) {
  const ScaledParams sp = computeScaled(net.scalesRig());
  NetworkPlotAxes a;
  a.style.seconds_per_tau = sp.time_scale_s / sp.epsilon;  // a network is physical
  a.tau_end = lastTau(files.orderRows());
  return a;
}

std::string networkOrderScript(const Network& net, const NetworkPlotAxes& axes,
                               const std::string& title, const std::string& data,
                               const std::string& png) {
  const int groups = static_cast<int>(net.platforms.size());
  std::ostringstream s;
  s << plotTerminal(axes.style.format, 1000, 500) << "set output " << gnuplotQuote(png) << "\n"
    << "set title " << gnuplotQuote(title) << " noenhanced\n"
    << timeAxis(axes.style, axes.tau_end) << "set ylabel 'r'\n"
    << "set yrange [0:1.05]\nset key outside right\nplot ";
  const std::string x = timeOf(axes.style, "$1");
  for (int g = 0; g < groups; ++g)
    s << gnuplotQuote(data) << " using " << x << ":" << g + 2 << " with lines title "
      << gnuplotQuote("r " + net.platforms[g].name) << " noenhanced, ";
  s << gnuplotQuote(data) << " using " << x << ":" << groups + 2
    << " with lines lw 2 title 'r (all)'\n";
  return s.str();
}

std::string networkRasterScript(const Network& net, const NetworkPlotAxes& axes,
                                const std::string& title, const std::string& data,
                                const std::string& png) {
  std::ostringstream s;
  s << plotTerminal(axes.style.format, 1000, 600) << "set output " << gnuplotQuote(png) << "\n"
    << "set title " << gnuplotQuote(title + " - phase relative to its platform") << " noenhanced\n"
    << timeAxis(axes.style, axes.tau_end) << "set ylabel 'metronome'\nset cbrange [-pi:pi]\n"
    << "set palette model HSV functions gray, 1, 0.9\nunset key\n"  // cyclic: -pi = pi
    << "set yrange [0.5:" << net.numMetronomes() + 0.5 << "]\n"
    << "plot " << gnuplotQuote(data) << " using " << timeOf(axes.style, "$1")
    << ":2:3 with points pt 5 ps 0.4 palette\n";
  return s.str();
}

std::vector<std::string> plotNetwork(const OutputDir& dir, const NetworkFiles& files,
                                     const Network& net, const std::string& title,
                                     const std::string& format) {
  std::vector<std::string> made;
  NetworkPlotAxes axes = networkPlotAxes(net, files);
  axes.style.format = format;
  const std::string order = "order." + format, raster = "raster." + format;
  if (drawPng(dir, order, rowsText(files.orderRows()),
              [&](const std::string& data, const std::string& out) {
                return networkOrderScript(net, axes, title, data, out);
              }))
    made.push_back(order);
  if (drawPng(dir, raster, rasterText(files.rasterRows()),
              [&](const std::string& data, const std::string& out) {
                return networkRasterScript(net, axes, title, data, out);
              }))
    made.push_back(raster);
  return made;
}

}  // namespace metrosync
