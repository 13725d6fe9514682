#include "tools/report/sweep_maps.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "base/constants.h"
#include "tools/report/plot.h"

namespace metrosync {

namespace {

constexpr int kMaxPanels = 4;  // metronomes shown in amplitudes.png and phases.png

// SPEC names first, in the order of SPEC 4, then the extensions; fixed colours (colour-blind
// friendly where it matters: in-phase, antiphase, suppression, death)
const std::vector<std::pair<std::string, std::string>>& fixedColours() {
  static const std::vector<std::pair<std::string, std::string>> c = {
      {"in-phase", "#0072b2"},  {"antiphase", "#d55e00"},   {"phase-locked", "#009e73"},
      {"drift", "#cc79a7"},     {"suppression", "#e69f00"}, {"death", "#000000"},
      {"unsettled", "#999999"}, {"alive", "#56b4e9"},       {"none", "#f0f0f0"},
      {"unknown", "#dddddd"},   {"failed", "#ff0000"},
  };
  return c;
}

// for the names of N >= 3 (clusters:..., suppressed:...), in legend order
const char* const kPalette[] = {"#f0e442", "#6a3d9a", "#8c564b", "#17becf", "#bcbd22",
                                "#9467bd", "#aec7e8", "#ffbb78", "#98df8a", "#ff9896",
                                "#c5b0d5", "#c49c94", "#f7b6d2", "#dbdb8d", "#9edae5",
                                "#393b79", "#637939", "#8c6d31", "#843c39", "#7b4173"};

}  // namespace

// Magenta and lime: in neither the regimes' fixed colours nor their palette.
const char* const kFoldCurveColour = "#ff00ff";
const char* const kHopfCurveColour = "#32cd32";

namespace {

// The axes drawn by default: the first two with more than one value (a single point is drawn
// along axis 0).
std::vector<size_t> drawnAxes(const SweepGrid& grid) {
  return mapAxes(grid, "");
}

bool isAngleKey(const std::string& key) {
  const size_t dot = key.rfind('.');
  const std::string last = dot == std::string::npos ? key : key.substr(dot + 1);
  return last == "phi" || last == "psi" || last == "angle" || last == "theta";
}

// tics in multiples of pi/2 (or coarser) for an angle axis
std::string piTics(const char* axis, double lo, double hi) {
  const double halves = (hi - lo) / (kPi / 2);
  long step = 1;
  for (long s : {1L, 2L, 4L, 8L, 20L, 40L}) {
    step = s;
    if (halves / s <= 8) break;
  }
  std::string tics;
  for (long k = static_cast<long>(std::ceil(lo / (kPi / 2) / step)) * step;
       k * (kPi / 2) <= hi + 1e-9 && tics.size() < 2000; k += step) {
    std::string label;
    const long a = std::labs(k);
    const std::string sign = k < 0 ? "-" : "";
    if (k == 0)
      label = "0";
    else if (a % 2 == 1)
      label = sign + (a == 1 ? "" : std::to_string(a)) + "π/2";
    else
      label = sign + (a == 2 ? "" : std::to_string(a / 2)) + "π";
    tics +=
        (tics.empty() ? "" : ", ") + std::string("\"") + label + "\" " + gnuplotNumber(k * kPi / 2);
  }
  return std::string("set ") + axis + "tics (" + tics + ")\n";
}

// Where a value sits along a map's axis: log10 of it for a log-spaced axis (even cells).
double mapCoordinate(const SweepAxis& a, double v) {
  return a.log ? std::log10(v) : v;
}

// range of an axis with half a cell on each side
struct AxisRange {
  double lo, hi, cell;
};
AxisRange axisRange(const SweepAxis& a) {
  const double front = mapCoordinate(a, a.value(0));
  const double back = mapCoordinate(a, a.value(a.count - 1));
  const double lo = std::min(front, back);
  const double hi = std::max(front, back);
  double cell = a.count > 1 ? (hi - lo) / (a.count - 1) : 0.0;
  if (!(cell > 0)) cell = std::max(1e-3, std::fabs(lo) * 0.1);
  return {lo - cell / 2, hi + cell / 2, cell};
}

std::string axisSettings(const SweepGrid& grid, const std::vector<size_t>& axes) {
  std::ostringstream s;
  const char* names[] = {"x", "y"};
  for (size_t k = 0; k < axes.size() && k < 2; ++k) {
    const SweepAxis& a = grid.axes()[axes[k]];
    const AxisRange r = axisRange(a);
    const std::string label = a.log ? "log10 " + a.key : a.key;
    s << "set " << names[k] << "label " << gnuplotQuote(label + (isAngleKey(a.key) ? " (rad)" : ""))
      << " noenhanced\n"
      << "set " << names[k] << "range [" << gnuplotNumber(r.lo) << ":" << gnuplotNumber(r.hi)
      << "]\n";
    if (isAngleKey(a.key) && r.hi - r.lo > 1.0) s << piTics(names[k], r.lo, r.hi);
  }
  return s.str();
}

long indexOf(const SweepGrid& grid, const std::vector<long>& c) {
  long g = 0;
  for (size_t a = 0; a < grid.axes().size(); ++a) g = g * grid.axes()[a].count + c[a];
  return g;
}

// The cells drawn, in scan order: y outer, x inner (2-D), with the grid index of each; a blank
// line (g = -1) between scan lines. Axes not drawn sit at their coordinate in `fixed`.
std::vector<long> scanOrder(const SweepGrid& grid, const std::vector<size_t>& axes,
                            std::vector<long> fixed) {
  std::vector<long> order;
  std::vector<long>& c = fixed;
  const long nx = grid.axes()[axes[0]].count;
  const long ny = axes.size() > 1 ? grid.axes()[axes[1]].count : 1;
  for (long iy = 0; iy < ny; ++iy) {
    for (long ix = 0; ix < nx; ++ix) {
      c[axes[0]] = ix;
      if (axes.size() > 1) c[axes[1]] = iy;
      order.push_back(indexOf(grid, c));
    }
    if (axes.size() > 1) order.push_back(-1);
  }
  return order;
}

std::string cellPosition(const SweepGrid& grid, const std::vector<size_t>& axes, long g) {
  const std::vector<long> c = grid.coordinates(g);
  const SweepAxis &x = grid.axes()[axes[0]], &y = grid.axes()[axes.size() > 1 ? axes[1] : 0];
  std::string s = gnuplotNumber(mapCoordinate(x, x.value(c[axes[0]])));
  if (axes.size() > 1) s += " " + gnuplotNumber(mapCoordinate(y, y.value(c[axes[1]])));
  return s;
}

long rgbOf(const std::string& hex) {
  return std::stol(hex.substr(1), nullptr, 16);
}

// What the maps show of one grid point: a fixed size whatever the number of metronomes (the first
// kMaxPanels amplitudes and phases are drawn), so that a slice's cells cost memory bounded by the
// slice, not by the sweep.
struct MapCell {
  bool present = false, complete = false;
  int regime = -1;  // its position in MapSummary::regimes
  double A[kMaxPanels], psi[kMaxPanels], r = NAN, s = NAN, fraction = NAN;
};

// a value shown in the maps: none for failed or missing points
double shown(const MapCell& c, double v) {
  return c.present && c.complete ? v : std::nan("");
}

std::string panelLayout(int panels) {
  const int cols = panels == 1 ? 1 : 2;
  const int rows = (panels + cols - 1) / cols;
  return std::to_string(rows) + "," + std::to_string(cols);
}

std::string header(const std::string& format, const std::string& png, int width, int height) {
  std::ostringstream s;
  s << plotTerminal(format, width, height) << "set output " << gnuplotQuote(png) << "\n"
    << "set tics out\n";
  return s.str();
}

}  // namespace

std::vector<std::string> regimeColours() {
  std::vector<std::string> out;
  for (const auto& [name, colour] : fixedColours()) out.push_back(colour);
  for (const char* c : kPalette) out.push_back(c);
  return out;
}

bool isSweepSliceMapName(const std::string& name) {
  for (const auto& m : sweepMapNames()) {
    if (m.size() < 4 || m.compare(m.size() - 4, 4, ".png") != 0) continue;
    const std::string stem = m.substr(0, m.size() - 4) + "--";
    if (name.size() > stem.size() + 4 && name.compare(0, stem.size(), stem) == 0 &&
        name.compare(name.size() - 4, 4, ".png") == 0)
      return true;
  }
  return false;
}

const std::vector<std::string>& sweepMapNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v = {"boundaries.csv"};
    for (const char* stem : {"regimes", "amplitudes", "phases", "order", "drive", "basin"})
      for (const std::string& format : plotFormats()) v.push_back(stem + ("." + format));
    return v;
  }();
  return names;
}

std::vector<std::string> regimeLegendOrder(const std::map<long, SweepPoint>& points) {
  std::map<std::string, long> count;
  for (const auto& [g, p] : points) ++count[p.regime];
  return regimeLegendOrder(count);
}

std::vector<std::string> regimeLegendOrder(const std::map<std::string, long>& count) {
  std::vector<std::string> legend;
  for (const auto& [name, colour] : fixedColours())
    if (count.count(name)) legend.push_back(name);
  std::vector<std::pair<long, std::string>> others;
  for (const auto& [name, k] : count) {
    const std::string& regime = name;  // a lambda captures no structured binding (C++17, clang)
    if (std::none_of(fixedColours().begin(), fixedColours().end(),
                     [&](const auto& f) { return f.first == regime; }))
      others.emplace_back(-k, name);
  }
  std::sort(others.begin(), others.end());  // most frequent first, then by name
  for (const auto& o : others) legend.push_back(o.second);
  return legend;
}

std::string regimeColour(const std::string& name, const std::vector<std::string>& legend) {
  for (const auto& [n, colour] : fixedColours())
    if (n == name) return colour;
  long k = 0;
  for (const auto& l : legend) {
    if (l == name) return kPalette[k % (sizeof kPalette / sizeof kPalette[0])];
    if (std::none_of(fixedColours().begin(), fixedColours().end(),
                     [&](const auto& f) { return f.first == l; }))
      ++k;
  }
  return "#808080";
}

namespace {

// The curves as a gnuplot datablock ($boundaries, one index per curve) and their plot clauses.
std::string boundaryBlock(const std::vector<continuation::FoldCurve>& curves) {
  std::ostringstream b;
  b << "$boundaries << EOD\n";
  for (const auto& c : curves) {
    for (const auto& q : c.points) b << gnuplotNumber(q.p1) << " " << gnuplotNumber(q.p2) << "\n";
    b << "\n\n";
  }
  b << "EOD\n";
  return b.str();
}

// Each curve over a white halo (visible on any regime's colour), in a colour no regime uses.
std::string boundaryPlot(const std::vector<continuation::FoldCurve>& curves) {
  std::string plot;
  bool fold_titled = false, hopf_titled = false;
  for (size_t i = 0; i < curves.size(); ++i) {
    const bool fold = curves[i].kind == continuation::CurveKind::Fold;
    bool& titled = fold ? fold_titled : hopf_titled;
    const std::string index = "$boundaries index " + std::to_string(i) + " using 1:2 with lines";
    plot += ", \\\n     " + index + " lc rgb 'white' lw 5 dt 1 notitle";
    plot += ", \\\n     " + index + " lc rgb '" + (fold ? kFoldCurveColour : kHopfCurveColour) +
            "' lw 2.5 dt " + (fold ? "1" : "2") +
            (titled ? " notitle"
             : fold ? " title 'fold curve'"
                    : " title 'Hopf curve'");
    titled = true;
  }
  return plot;
}

}  // namespace

std::string boundariesCsv(const std::vector<continuation::FoldCurve>& curves,
                          const std::string& key1, const std::string& key2) {
  std::ostringstream c;
  c << "curve,type," << key1 << "," << key2 << "\n";
  for (size_t i = 0; i < curves.size(); ++i)
    for (const auto& q : curves[i].points)
      c << i << "," << toString(curves[i].kind) << "," << gnuplotNumber(q.p1) << ","
        << gnuplotNumber(q.p2) << "\n";
  return c.str();
}

nlohmann::json boundariesJson(const std::vector<continuation::FoldCurve>& curves) {
  nlohmann::json list = nlohmann::json::array();
  for (size_t i = 0; i < curves.size(); ++i) {
    nlohmann::json c = {{"curve", i},
                        {"type", toString(curves[i].kind)},
                        {"points", curves[i].points.size()},
                        {"end_backward", curves[i].end_backward},
                        {"end_forward", curves[i].end_forward}};
    if (!curves[i].failure.empty())
      c["failure"] = curves[i].failure, c["seed"] = {curves[i].seed_p1, curves[i].seed_p2};
    list.push_back(c);
  }
  return list;
}

std::string regimeMapScript(const std::string& data_path, const std::string& png_path,
                            const SweepGrid& grid, const std::vector<std::string>& legend,
                            const std::string& title, const std::string& format,
                            const std::vector<continuation::FoldCurve>& boundaries,
                            const std::vector<size_t>& map_axes) {
  const std::vector<size_t> axes = map_axes.empty() ? drawnAxes(grid) : map_axes;
  const bool map2d = axes.size() > 1;
  std::ostringstream s;
  s << header(format, png_path, 1100, map2d ? 850 : 420) << "set title " << gnuplotQuote(title)
    << " noenhanced font 'sans,13'\n"
    << "set key at screen 0.75, graph 1 left top Left reverse noenhanced title 'regime' "
       "samplen 1.5\n"
    << "set rmargin at screen 0.72\n"
    << axisSettings(grid, axes);
  std::string plot;
  if (map2d) {
    if (!boundaries.empty()) s << boundaryBlock(boundaries);
    plot = "plot " + gnuplotQuote(data_path) + " using 1:2:3:4:5 with rgbimage notitle";
    plot += boundaryPlot(boundaries);
  } else {
    const AxisRange r = axisRange(grid.axes()[axes[0]]);
    s << "set yrange [0:1]\nunset ytics\n";
    plot = "plot " + gnuplotQuote(data_path) + " using 1:($2 < 0 ? NaN : 1):(" +
           gnuplotNumber(r.cell) +
           "):($2 < 0 ? 0 : $2) with boxes fill solid 1.0 noborder lc rgb variable notitle";
  }
  for (const auto& name : legend)
    plot += ", \\\n     keyentry with boxes fill solid 1.0 border lc rgb '#606060' fc rgb '" +
            regimeColour(name, legend) + "' title " + gnuplotQuote(name);
  s << plot << "\nset output\n";
  return s.str();
}

namespace {

// What every picture of one sweep shares.
struct MapFrame {
  const OutputDir& dir;
  const SweepGrid& grid;
  std::vector<size_t> axes;  // the drawn axes
  bool map2d = false;
  std::vector<long> order;  // scan order, -1 between rows
  std::vector<long> fixed;  // the slice: the coordinates of the axes not drawn
  std::string title;
  std::string format = "png";  // png, svg or pdf (tools/report/plot.h)
  std::string suffix;          // "" or "--KEY3=V..." (a slice of an N-D sweep)
  // "regimes.png" of this slice in this format: "regimes--KEY3=V.svg"
  std::string file(const std::string& png_name) const {
    return png_name.substr(0, png_name.rfind('.')) + suffix + "." + format;
  }
};

// What the maps need of the whole sweep, gathered in one reading of its points.
struct MapSummary {
  std::vector<std::string> regimes;  // every regime name, in first-seen order
  std::vector<std::string> legend;   // regimeLegendOrder of their counts
  long points = 0;
  bool any_complete = false, any_drive = false;
};

MapSummary summarize(const SweepPointSource& points) {
  MapSummary m;
  std::map<std::string, long> count;
  points(
      [&](const SweepPoint& p) {
        if (count[p.regime]++ == 0) m.regimes.push_back(p.regime);
        ++m.points;
        m.any_complete = m.any_complete || p.complete;
        m.any_drive = m.any_drive || !std::isnan(p.s);
      },
      {});
  m.legend = regimeLegendOrder(count);
  return m;
}

// The cells of one slice, in scan order (f.order without its blank lines), read from `points`.
std::vector<MapCell> sliceCells(const MapFrame& f, const MapSummary& m,
                                const SweepPointSource& points) {
  const long nx = f.grid.axes()[f.axes[0]].count;
  const long ny = f.map2d ? f.grid.axes()[f.axes[1]].count : 1;
  std::map<std::string, int> regime;
  for (std::size_t k = 0; k < m.regimes.size(); ++k) regime[m.regimes[k]] = static_cast<int>(k);
  std::vector<MapCell> cells(static_cast<std::size_t>(nx * ny));
  // a line of another slice differs in the text of an axis not drawn (the first columns)
  std::vector<std::string> keys;
  for (std::size_t a = 0; a < f.grid.axes().size(); ++a)
    keys.push_back(a == f.axes[0] || (f.map2d && a == f.axes[1])
                       ? std::string()
                       : f.grid.axes()[a].text(f.fixed[a]) + ",");
  const auto inSlice = [&](const std::string& line) {
    std::size_t at = 0;
    for (const std::string& key : keys) {
      const std::size_t comma = line.find(',', at);
      if (comma == std::string::npos) return true;  // malformed: the parser says so
      if (!key.empty() && line.compare(at, comma + 1 - at, key) != 0) return false;
      at = comma + 1;
    }
    return true;
  };
  points(
      [&](const SweepPoint& p) {
        const std::vector<long> at = f.grid.coordinates(p.index);
        for (std::size_t a = 0; a < at.size(); ++a)  // the axes not drawn: this slice's values
          if (a != f.axes[0] && !(f.map2d && a == f.axes[1]) && at[a] != f.fixed[a]) return;
        MapCell& c =
            cells[static_cast<std::size_t>((f.map2d ? at[f.axes[1]] : 0) * nx + at[f.axes[0]])];
        c.present = true;
        c.complete = p.complete;
        c.regime = regime.at(p.regime);
        for (int i = 0; i < kMaxPanels; ++i) {
          c.A[i] = i < static_cast<int>(p.A.size()) ? p.A[i] : NAN;
          c.psi[i] = i < static_cast<int>(p.psi.size()) ? p.psi[i] : NAN;
        }
        c.r = p.r;
        c.s = p.s;
        c.fraction = p.in_phase_fraction;
      },
      inSlice);
  return cells;
}

// regimes.png: "x y R G B" cells (2-D; white where not run), or "x rgb" (1-D; -1 not run)
bool drawRegimeMap(const MapFrame& f, const MapSummary& m, const std::vector<MapCell>& cells,
                   const std::vector<continuation::FoldCurve>& boundaries) {
  std::ostringstream d;
  std::size_t k = 0;
  for (long g : f.order) {
    if (g < 0) {
      d << "\n";
      continue;
    }
    const MapCell& c = cells[k++];
    const long rgb =
        c.present ? rgbOf(regimeColour(m.regimes[c.regime], m.legend)) : (f.map2d ? 0xffffff : -1);
    d << cellPosition(f.grid, f.axes, g);
    if (f.map2d)
      d << " " << ((rgb >> 16) & 255) << " " << ((rgb >> 8) & 255) << " " << (rgb & 255) << "\n";
    else
      d << " " << rgb << "\n";
  }
  return drawPng(f.dir, f.file("regimes.png"), d.str(),
                 [&](const std::string& data, const std::string& png) {
                   return regimeMapScript(data, png, f.grid, m.legend, f.title + " - regimes",
                                          f.format, boundaries, f.axes);
                 });
}

// The values: "x [y] A_1..A_k psi_2..psi_l r log10(s) fraction" (NaN where not run or failed),
// k = min(N, kMaxPanels) and l - 1 = min(N - 1, kMaxPanels): the columns the pictures draw.
std::string valuesData(const MapFrame& f, int n, const std::vector<MapCell>& cells) {
  std::ostringstream d;
  std::size_t k = 0;
  for (long g : f.order) {
    if (g < 0) {
      d << "\n";
      continue;
    }
    const MapCell& c = cells[k++];
    d << cellPosition(f.grid, f.axes, g);
    for (int i = 0; i < std::min(n, kMaxPanels); ++i) d << " " << gnuplotNumber(shown(c, c.A[i]));
    for (int j = 0; j < std::min(n - 1, kMaxPanels); ++j)
      d << " " << gnuplotNumber(shown(c, c.psi[j]));
    d << " " << gnuplotNumber(shown(c, c.r));
    // log10 s, clamped to [-2, 2] (s = inf: a free platform, drawn as slipping)
    d << " "
      << gnuplotNumber(
             shown(c, std::isnan(c.s) ? NAN : std::max(-2.0, std::min(2.0, std::log10(c.s)))));
    d << " " << gnuplotNumber(shown(c, c.fraction)) << "\n";
  }
  return d.str();
}

// One picture of up to four quantities (gnuplot columns of the values data).
struct Quantity {
  std::string label;
  int column;
};
struct Picture {
  std::string name;  // file name
  std::vector<Quantity> qs;
  std::string palette, range;
  bool angle = false;  // a phase in [0, 2 pi): pi tics, points not lines
};

// Maps (2-D) or lines against the key (1-D).
std::string pictureScript(const MapFrame& f, const Picture& pic, const std::string& data,
                          const std::string& png) {
  std::ostringstream s;
  const int panels = f.map2d ? static_cast<int>(pic.qs.size()) : 1;
  const std::string title = f.title + " - " + pic.name.substr(0, pic.name.size() - 4);
  s << header(f.format, png, 1100, f.map2d ? (panels > 2 ? 950 : 520) : 480)
    << axisSettings(f.grid, f.axes);
  if (f.map2d) {
    s << "set multiplot layout " << panelLayout(panels) << " title " << gnuplotQuote(title)
      << " noenhanced\n"
      << pic.palette << "set cbrange " << pic.range << "\n";
    if (pic.angle) s << piTics("cb", 0.0, 2 * kPi);
    for (const auto& q : pic.qs)
      s << "set title " << gnuplotQuote(q.label) << "\nplot " << gnuplotQuote(data)
        << " using 1:2:" << q.column << " with image notitle\n";
    s << "unset multiplot\n";
  } else {
    s << "set title " << gnuplotQuote(title) << " noenhanced\nset key outside right top\nset grid\n"
      << "set yrange " << pic.range << "\n";
    if (pic.angle) s << piTics("y", 0.0, 2 * kPi);
    std::string plot;
    const char* const colours[] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7"};
    for (size_t k = 0; k < pic.qs.size(); ++k)
      plot += (plot.empty() ? "plot " : ", \\\n     ") + gnuplotQuote(data) +
              " using 1:" + std::to_string(pic.qs[k].column) +
              (pic.angle ? " with points pt 7 ps 0.6" : " with linespoints pt 7 ps 0.5") +
              " lc rgb '" + colours[k % 4] + "' title " + gnuplotQuote(pic.qs[k].label);
    s << plot << "\n";
  }
  s << "set output\n";
  return s.str();
}

// The pictures of the values: amplitudes, phases, order parameter (N >= 3), drive (Coulomb).
std::vector<Picture> valuePictures(int n, int first_value, bool any_drive, long basin_samples) {
  std::vector<Quantity> amps, phases;
  const int shown_a = std::min(n, kMaxPanels), shown_psi = std::min(n - 1, kMaxPanels);
  for (int i = 0; i < shown_a; ++i) amps.push_back({"A_" + std::to_string(i + 1), first_value + i});
  for (int j = 0; j < shown_psi; ++j)
    phases.push_back({"ψ_" + std::to_string(j + 2), first_value + shown_a + j});
  const int r_column = first_value + shown_a + shown_psi;  // then log10 s, then the fraction
  const std::string viridis =
      "set palette defined (0 '#440154', 1 '#3b528b', 2 '#21918c', 3 '#5ec962', 4 '#fde725')\n";
  // hue around the circle: psi = 0 and 2 pi get the same colour
  const std::string cyclic = "set palette model HSV defined (0 0 0.75 0.95, 1 1 0.75 0.95)\n";
  // where the platform sticks (s < 1: blue) and the metronomes are uncoupled
  const std::string diverging = "set palette defined (-2 '#2166ac', 0 '#f7f7f7', 2 '#b2182b')\n";
  std::vector<Picture> pics = {{"amplitudes.png", amps, viridis, "[0:*]", false},
                               {"phases.png", phases, cyclic, "[0:2*pi]", true}};
  if (n >= 3)
    pics.push_back(
        {"order.png", {{"r = |Σ A_j e^{iφ_j}| / Σ A_j", r_column}}, viridis, "[0:1]", false});
  if (any_drive)
    pics.push_back(
        {"drive.png",
         {{"log_{10} s,  s = |Σ A_j e^{iφ_j}| / μ  (s < 1: the platform sticks)", r_column + 1}},
         diverging,
         "[-2:2]",
         false});
  if (basin_samples > 0)
    pics.push_back({"basin.png",
                    {{"in-phase fraction of " + std::to_string(basin_samples) + " random starts",
                      r_column + 2}},
                    viridis,
                    "[0:1]",
                    false});
  return pics;
}

}  // namespace

namespace {

// The maps of one slice (all of them for a grid of two axes or fewer).
std::vector<std::string> plotSlice(MapFrame& f, int n, const MapSummary& m,
                                   const SweepPointSource& points,
                                   const std::vector<continuation::FoldCurve>& boundaries) {
  std::vector<std::string> written;
  const std::vector<MapCell> cells = sliceCells(f, m, points);
  if (drawRegimeMap(f, m, cells, boundaries)) written.push_back(f.file("regimes.png"));
  if (!m.any_complete) return written;  // every point failed: no value to draw
  const std::string values = valuesData(f, n, cells);
  const int first_value = f.map2d ? 3 : 2;  // gnuplot column of A_1
  for (const Picture& pic : valuePictures(n, first_value, m.any_drive, f.grid.basin().samples)) {
    if (pic.qs.empty()) continue;
    auto script = [&](const std::string& data, const std::string& png) {
      return pictureScript(f, pic, data, png);
    };
    if (drawPng(f.dir, f.file(pic.name), values, script)) written.push_back(f.file(pic.name));
  }
  return written;
}

// The axes of more than one value that the maps do not draw: each of their combinations is a
// slice.
std::vector<size_t> slicedAxes(const SweepGrid& grid, const std::vector<size_t>& drawn) {
  std::vector<size_t> s;
  for (size_t k = 0; k < grid.axes().size(); ++k)
    if (grid.axes()[k].count > 1 && std::find(drawn.begin(), drawn.end(), k) == drawn.end())
      s.push_back(k);
  return s;
}

// "--KEY=V--KEY2=W" for a file name ('*' as "all", '/' as "_"), and "KEY = V, KEY2 = W"
std::pair<std::string, std::string> sliceNames(const SweepGrid& grid,
                                               const std::vector<size_t>& sliced,
                                               const std::vector<long>& c) {
  std::string file, title;
  for (size_t k : sliced) {
    const SweepAxis& a = grid.axes()[k];
    std::string part = a.key + "=" + a.text(c[k]);
    title += (title.empty() ? "" : ", ") + a.key + " = " + a.text(c[k]);
    for (char& ch : part)
      if (ch == '/' || ch == ' ') ch = '_';
    for (size_t at = part.find('*'); at != std::string::npos; at = part.find('*'))
      part.replace(at, 1, "all");
    file += "--" + part;
  }
  return {file, title};
}

}  // namespace

std::vector<std::string> plotSweepMaps(const OutputDir& dir, const SweepGrid& grid, int n,
                                       const SweepPointSource& points, const std::string& title,
                                       const std::string& format,
                                       const std::vector<continuation::FoldCurve>& boundaries,
                                       const std::vector<size_t>& map_axes) {
  std::vector<std::string> written;
  if (grid.size() == 0 || n < 1) return written;   // nothing to draw
  if (grid.size() > kMaxMapCells) return written;  // more cells than pixels
  const MapSummary summary = summarize(points);
  if (summary.points == 0) return written;
  MapFrame f{dir,    grid, map_axes.empty() ? drawnAxes(grid) : map_axes, false, {}, {}, title,
             format, ""};
  f.map2d = f.axes.size() > 1;
  // the curves live in the plane of axes 0 and 1
  const bool curves = f.axes == std::vector<size_t>{0, 1};
  const std::vector<size_t> sliced = slicedAxes(grid, f.axes);
  long slices = 1;
  for (size_t k : sliced) slices = std::min(kMaxMapSlices + 1, slices * grid.axes()[k].count);
  if (slices > kMaxMapSlices)
    std::cerr << "metrosync: warning: the maps show only the first " << kMaxMapSlices
              << " combinations of the axes not drawn (choose the drawn ones with --map)\n";
  std::vector<long> c(grid.axes().size(), 0);
  for (long s = 0; s < std::min(slices, kMaxMapSlices); ++s) {
    const auto [file, slice_title] = sliceNames(grid, sliced, c);
    f.suffix = file;
    f.title = slice_title.empty() ? title : title + " (" + slice_title + ")";
    f.order = scanOrder(grid, f.axes, c);
    f.fixed = c;
    for (auto& w : plotSlice(f, n, summary, points,
                             curves ? boundaries : std::vector<continuation::FoldCurve>{}))
      written.push_back(w);
    for (size_t k = sliced.size(); k-- > 0;) {  // the next combination, the last axis fastest
      if (++c[sliced[k]] < grid.axes()[sliced[k]].count) break;
      c[sliced[k]] = 0;
    }
  }
  return written;
}

}  // namespace metrosync
