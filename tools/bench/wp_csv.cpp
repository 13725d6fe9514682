#include "tools/bench/wp_csv.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "base/csv.h"

namespace metrosync::bench {

namespace {

const char* const kColumns[] = {
    "scene",     "n",         "periods",      "engine",         "integrator",
    "setting",   "status",    "runs",         "wall_median_s",  "cpu_median_s",
    "load1_min", "load1_max", "err_envelope", "err_final_state"};

// A row's fields by column name, with its place for error messages.
struct Row {
  const std::map<std::string, size_t>* col;
  std::vector<std::string> f;
  std::string where;  // "source line L"
  const std::string& text(const std::string& key) const { return f[col->at(key)]; }
  bool has(const std::string& key) const { return col->count(key) > 0; }
  double num(const std::string& key) const {
    return csvNumber(text(key), where + ", column " + key);
  }
};

void addRow(VerdictScene& s, const Row& r, const Sides& sides) {
  const std::string engine = r.text("engine"), status = r.text("status");
  const std::string label = engine + ":" + r.text("integrator");
  const std::string method = label + ":" + r.text("setting");
  if (status == "reference") {
    s.reference_engine = engine;
    s.reference = method;
  } else if (status == "cross-check") {
    s.cross_checks.push_back({engine, method, r.num("err_final_state"), r.num("err_envelope")});
  } else if (status == "not run" && engine == sides.peer) {
    s.peer_skipped = r.has("note") && !r.text("note").empty() ? r.text("note") : "not run";
  } else if (status == "ok" &&
             (engine == sides.ours || engine == sides.peer || engine == sides.run)) {
    SidePoint p{method,
                r.num("err_final_state"),
                r.num("err_envelope"),
                r.num("cpu_median_s"),
                r.num("wall_median_s"),
                static_cast<int>(r.num("runs"))};
    // the runs without samples (columns absent from the files of earlier versions)
    if (r.has("cpu_final_median_s")) p.cpu_final_s = r.num("cpu_final_median_s");
    if (r.has("wall_final_median_s")) p.wall_final_s = r.num("wall_final_median_s");
    if (r.has("engine_median_s")) p.engine_s = r.num("engine_median_s");
    if (r.has("wall_over_engine")) p.wall_over_engine = r.num("wall_over_engine");
    auto& pts = engine == sides.ours ? s.ours : engine == sides.peer ? s.peer : s.run;
    auto& labels = engine == sides.ours   ? s.our_methods
                   : engine == sides.peer ? s.peer_methods
                                          : s.run_methods;
    pts.push_back(p);
    if (std::find(labels.begin(), labels.end(), label) == labels.end()) labels.push_back(label);
    s.load_min = std::fmin(s.load_min, r.num("load1_min"));  // fmin, fmax: NaN is "none yet"
    s.load_max = std::fmax(s.load_max, r.num("load1_max"));
  }
}

}  // namespace

std::vector<std::string> csvCellsAt(const std::string& line, const std::string& where) {
  try {
    return csvCells(line);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where + ": " + e.what());
  }
}

double csvNumber(const std::string& s, const std::string& where) {
  if (s.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::optional<double> v = metrosync::csvNumber(s);
  if (!v) throw std::invalid_argument(where + ": '" + s + "' is not a number");
  return *v;
}

std::vector<VerdictScene> parseWorkPrecisionCsv(const std::string& text, const std::string& source,
                                                const Sides& sides) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line)) throw std::invalid_argument(source + ": empty, no CSV header");
  std::map<std::string, size_t> col;
  const std::vector<std::string> header = csvCellsAt(line, source + " line 1");
  for (size_t k = 0; k < header.size(); ++k) col[header[k]] = k;
  for (const char* c : kColumns)
    if (!col.count(c))
      throw std::invalid_argument(source + " line 1: no column '" + c +
                                  "' (not a metrosync_bench precision CSV)");
  std::vector<VerdictScene> scenes;
  for (int lineno = 2; std::getline(in, line); ++lineno) {
    if (line.empty()) continue;
    const std::string where = source + " line " + std::to_string(lineno);
    Row r{&col, csvCellsAt(line, where), where};
    if (r.f.size() != header.size())
      throw std::invalid_argument(r.where + ": " + std::to_string(r.f.size()) + " fields, the " +
                                  "header has " + std::to_string(header.size()));
    auto it = std::find_if(scenes.begin(), scenes.end(),
                           [&](const VerdictScene& s) { return s.name == r.text("scene"); });
    if (it == scenes.end()) {
      scenes.emplace_back();
      it = scenes.end() - 1;
      it->name = r.text("scene");
    }
    if (it->n == 0) it->n = static_cast<int>(r.num("n"));
    if (!(it->periods > 0)) it->periods = r.num("periods");
    addRow(*it, r, sides);
  }
  return scenes;
}

}  // namespace metrosync::bench
