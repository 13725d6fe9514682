#include "tools/report/basin_files.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "base/constants.h"
#include "base/number_text.h"
#include "sim/record/atomic_file.h"
#include "tools/report/plot.h"
#include "tools/report/sweep_maps.h"

namespace metrosync {

namespace {

// The range a key's axis shows: its FROM:TO, or the circle for an angle.
std::pair<double, double> shownRange(const RandomKey& k) {
  if (k.angle) return {0.0, 2 * kPi};
  return {k.from, k.to};
}

std::string basinScript(const std::vector<RandomKey>& keys, const std::vector<std::string>& legend,
                        const std::string& title, const std::string& data, const std::string& png) {
  std::ostringstream s;
  s << "set terminal pngcairo size 1000,850 enhanced font 'sans,11' linewidth 1.2\n"
    << "set output " << gnuplotQuote(png) << "\nset tics out\n"
    << "set title " << gnuplotQuote(title) << " noenhanced font 'sans,13'\n"
    << "set key at screen 0.75, graph 1 left top Left reverse noenhanced title 'regime' "
       "samplen 1.5\nset rmargin at screen 0.72\n";
  const char* axis[] = {"x", "y"};
  for (int a = 0; a < 2; ++a) {
    const auto [lo, hi] = shownRange(keys[a]);
    s << "set " << axis[a] << "label "
      << gnuplotQuote(keys[a].key + (keys[a].angle ? " (rad)" : "")) << " noenhanced\nset "
      << axis[a] << "range [" << numberText(lo, 12) << ":" << numberText(hi, 12) << "]\n";
    if (keys[a].angle)
      s << "set " << axis[a]
        << "tics (\"0\" 0, \"π/2\" pi/2, \"π\" pi, \"3π/2\" 3*pi/2, \"2π\" 2*pi)\n";
  }
  s << "plot " << gnuplotQuote(data)
    << " using 1:2:3 with points pt 7 ps 0.7 lc rgb variable notitle";
  for (const auto& name : legend)
    s << ", \\\n     keyentry with points pt 7 ps 1.5 lc rgb '" << regimeColour(name, legend)
      << "' title " << gnuplotQuote(name);
  s << "\nset output\n";
  return s.str();
}

}  // namespace

std::string basinCsvHeader(const std::vector<RandomKey>& keys, int n) {
  std::string h = "sample";
  for (const auto& k : keys) h += "," + k.key;
  h += ",regime";
  for (int i = 1; i <= n; ++i) h += ",A_" + std::to_string(i);
  for (int j = 2; j <= n; ++j) h += ",psi_" + std::to_string(j);
  return h + ",complete";
}

std::string basinCsvRow(const BasinSample& s) {
  std::string r = std::to_string(s.point.index);
  for (const auto& d : s.drawn) r += "," + d;
  r += "," + s.point.regime;
  for (double a : s.point.A) r += "," + numberText(a, 12);
  for (double p : s.point.psi) r += "," + numberText(p, 12);
  return r + (s.point.complete ? ",1" : ",0");
}

BasinRows::BasinRows() : rows_(temporaryFolder()) {}

void BasinRows::add(const BasinSample& s) {
  rows_.add(s.point.index, s.point.regime + "\t" + basinCsvRow(s));
  ++added_;
}

void BasinRows::forEach(const std::function<void(const std::string&, const std::string&)>& visit) {
  rows_.forEachIndex([&](long, const std::vector<std::string>& lines) {
    const std::string& line = lines.back();  // a sample given twice: its last row
    const std::size_t tab = line.find('\t');
    visit(line.substr(tab + 1), line.substr(0, tab));
  });
}

void BasinRows::tally() {
  regimes_.clear();
  count_ = failed_ = 0;
  forEach([&](const std::string& row, const std::string& regime) {
    ++regimes_[regime];
    ++count_;
    failed_ += row.compare(row.size() - 2, 2, ",1") != 0;  // the complete column
  });
}

void BasinRows::writeCsv(const std::string& path, const std::vector<RandomKey>& keys, int n) {
  AtomicFile out(path);
  out.writeLine(basinCsvHeader(keys, n));
  forEach([&](const std::string& row, const std::string&) { out.writeLine(row); });
  out.commit();
}

nlohmann::json fractionsJson(const std::vector<RegimeFraction>& fractions) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& f : fractions)
    a.push_back({{"regime", f.regime},
                 {"count", f.count},
                 {"fraction", f.fraction},
                 {"ci95", {f.ci.lo, f.ci.hi}}});
  return a;
}

nlohmann::json randomKeysJson(const std::vector<RandomKey>& keys) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& k : keys)
    a.push_back(
        {{"key", k.key}, {"spec", k.spec}, {"from", k.from}, {"to", k.to}, {"angle", k.angle}});
  return a;
}

std::string fractionsTable(const std::vector<RegimeFraction>& fractions, long samples) {
  size_t width = 6;
  for (const auto& f : fractions) width = std::max(width, f.regime.size());
  std::ostringstream t;
  char line[200];
  std::snprintf(line, sizeof line, "  %-*s %8s %9s   %s\n", static_cast<int>(width), "regime",
                "count", "fraction", "95% interval (Wilson)");
  t << line;
  for (const auto& f : fractions) {
    std::snprintf(line, sizeof line, "  %-*s %8ld %9.4f   [%.4f, %.4f]\n", static_cast<int>(width),
                  f.regime.c_str(), f.count, f.fraction, f.ci.lo, f.ci.hi);
    t << line;
  }
  t << "  (" << samples << " samples)\n";
  return t.str();
}

bool plotBasinMap(const OutputDir& dir, const std::vector<RandomKey>& keys, BasinRows& samples,
                  const std::string& title) {
  if (keys.size() != 2 || samples.count() == 0) return false;
  const std::vector<std::string> legend = regimeLegendOrder(samples.regimes());
  const auto data = [&](std::ostream& d) {
    samples.forEach([&](const std::string& row, const std::string& regime) {
      // "sample,drawn_1,drawn_2,...": the drawn values are numbers (no comma in them)
      const std::size_t a = row.find(',') + 1, b = row.find(',', a), c = row.find(',', b + 1);
      d << row.substr(a, b - a) << " " << row.substr(b + 1, c - b - 1) << " "
        << std::stol(regimeColour(regime, legend).substr(1), nullptr, 16) << "\n";
    });
  };
  return drawPngFrom(dir, "basin.png", data,
                     [&](const std::string& data_path, const std::string& png) {
                       return basinScript(keys, legend, title, data_path, png);
                     });
}

}  // namespace metrosync
