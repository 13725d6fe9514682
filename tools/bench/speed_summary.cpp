#include "tools/bench/speed_summary.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "base/number_text.h"
#include "tools/bench/bench_metrics.h"
#include "tools/bench/peer_verdict.h"
#include "tools/bench/wp_csv.h"

namespace metrosync::bench {

const char* const kSpeedBegin = "<!-- speed:begin";
const char* const kSpeedEnd = "<!-- speed:end";
const char* const kDefaultRig = "yaml/rigs/experiment.yaml";

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  if (!in) return "";
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A CSV as rows of named fields.
struct Csv {
  std::vector<std::map<std::string, std::string>> rows;
  std::string source;
  double number(size_t row, const std::string& key) const {
    const auto it = rows[row].find(key);
    if (it == rows[row].end()) throw std::invalid_argument(source + ": no column '" + key + "'");
    if (it->second.empty()) return kNaN;
    size_t used = 0;
    double v = kNaN;
    try {
      v = std::stod(it->second, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != it->second.size())
      throw std::invalid_argument(source + " line " + std::to_string(row + 2) + ", column " + key +
                                  ": '" + it->second + "' is not a number");
    return v;
  }
  const std::string& text(size_t row, const std::string& key) const {
    const auto it = rows[row].find(key);
    if (it == rows[row].end()) throw std::invalid_argument(source + ": no column '" + key + "'");
    return it->second;
  }
};

Csv parseCsv(const std::string& text, const std::string& source) {
  Csv csv;
  csv.source = source;
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line)) return csv;
  const std::vector<std::string> header = splitCsvLine(line);
  for (int lineno = 2; std::getline(in, line); ++lineno) {
    if (line.empty()) continue;
    const std::vector<std::string> f = splitCsvLine(line);
    if (f.size() != header.size())
      throw std::invalid_argument(source + " line " + std::to_string(lineno) + ": " +
                                  std::to_string(f.size()) + " fields, the header has " +
                                  std::to_string(header.size()));
    std::map<std::string, std::string> row;
    for (size_t k = 0; k < f.size(); ++k) row[header[k]] = f[k];
    csv.rows.push_back(row);
  }
  return csv;
}

void widen(double v, double& lo, double& hi) {
  if (!std::isfinite(v)) return;
  lo = std::fmin(lo, v);
  hi = std::fmax(hi, v);
}

// The headline cells (final-state error, CPU) grouped by N; the peer's skipped scenes left out.
void ratioFacts(const Csv& c, SpeedFacts& f) {
  std::map<int, SpeedFacts::Group> groups;
  std::vector<std::string> scenes;
  for (size_t r = 0; r < c.rows.size(); ++r) {
    if (c.text(r, "measure") != "final-state" || c.text(r, "clock") != "CPU") continue;
    if (c.text(r, "reason").rfind(kPeerNotRun, 0) == 0) continue;
    const int n = static_cast<int>(c.number(r, "n"));
    SpeedFacts::Group& g = groups[n];
    if (g.cells == 0) g.n = n, g.lo = g.hi = kNaN;
    ++g.cells;
    const double ratio = c.number(r, "ratio");
    if (ratio >= kTargetRatio) ++g.met;
    widen(ratio, g.lo, g.hi);
    widen(c.number(r, "error"), f.err_lo, f.err_hi);
    if (std::find(scenes.begin(), scenes.end(), c.text(r, "scene")) == scenes.end())
      scenes.push_back(c.text(r, "scene"));
  }
  for (const auto& [n, g] : groups) f.groups.push_back(g);
  f.scenes = static_cast<int>(scenes.size());
}

void slopeFacts(const Csv& c, SpeedFacts& f) {
  for (size_t r = 0; r < c.rows.size(); ++r) {
    if (c.text(r, "measure") != "final-state" || c.text(r, "clock") != "CPU" ||
        c.text(r, "side") != "metrosync")
      continue;
    widen(c.number(r, "slope"), f.slope_lo, f.slope_hi);
    if (!std::isfinite(c.number(r, "time_per_period_s"))) continue;
    const int n = static_cast<int>(c.number(r, "n"));
    f.slope_n_lo = f.slope_n_lo == 0 ? n : std::min(f.slope_n_lo, n);
    f.slope_n_hi = std::max(f.slope_n_hi, n);
  }
}

void runFacts(const Csv& c, SpeedFacts& f) {
  for (size_t r = 0; r < c.rows.size(); ++r) {
    if (!c.text(r, "failure").empty()) continue;
    ++f.run_rows;
    if (c.rows[r].count("inconsistent_splits"))
      f.run_inconsistent += static_cast<int>(c.number(r, "inconsistent_splits"));
    const double ratio = c.number(r, "ratio");
    f.run_target = c.number(r, "target");  // the CSV carries the target it was measured against
    if (ratio <= f.run_target) ++f.run_met;
    widen(ratio, f.run_ratio_lo, f.run_ratio_hi);
    widen(c.number(r, "load1_min"), f.load_lo, f.load_hi);
    widen(c.number(r, "load1_max"), f.load_lo, f.load_hi);
    if (c.text(r, "scene") == kDefaultRig && c.text(r, "variant").empty()) {
      f.default_wall = c.number(r, "wall_seconds");
      f.default_engine = c.number(r, "engine_seconds");
      f.default_process = c.number(r, "process_wall_s");
    }
  }
}

void mapFacts(const Csv& c, SpeedFacts& f) {
  for (size_t r = 0; r < c.rows.size(); ++r) {
    if (!c.text(r, "failure").empty()) continue;
    const bool full = c.text(r, "map") == "full";
    (full ? f.full_map_s : f.slow_map_s) = c.number(r, "wall_s");
    (full ? f.full_target_s : f.slow_target_s) = c.number(r, "target_s");
    widen(c.number(r, "load1_min"), f.load_lo, f.load_hi);
    widen(c.number(r, "load1_max"), f.load_lo, f.load_hi);
  }
}

// "1.2-3.4x" (or "1.2x" when both ends agree to the digits printed)
std::string range(double lo, double hi, const std::string& unit = "x") {
  const std::string a = benchNumber(lo, 2, Notation::Fixed),
                    b = benchNumber(hi, 2, Notation::Fixed);
  return (a == b ? a : a + "-" + b) + unit;
}

std::string ratioSentence(const SpeedFacts& f) {
  if (f.groups.empty())
    return "The careful peer was not measured in this run (it was missing: see the folder's "
           "README), so there is no ratio at equal error. ";
  std::ostringstream os;
  os << "Against a careful C++17 program on Boost.Odeint (the project's independent peer, not "
        "part of this repository: dopri5 and Fehlberg 7(8), fixed-size state, the same equations "
        "and events), at equal final-state error "
        "from "
     << errorLabel(f.err_hi) << " to " << errorLabel(f.err_lo)
     << " (CPU medians, integration and events only on both sides), the direct engine is ";
  int cells = 0, met = 0;
  for (size_t k = 0; k < f.groups.size(); ++k) {
    const SpeedFacts::Group& g = f.groups[k];
    os << (k == 0                     ? ""
           : k + 1 == f.groups.size() ? " and "
                                      : ", ")
       << (std::isfinite(g.lo) ? range(g.lo, g.hi) : std::string("not comparable"))
       << " the peer's speed with " << g.n << " metronomes";
    cells += g.cells, met += g.met;
  }
  os << " over " << f.scenes << " scenes: issue 23's target of "
     << benchNumber(kTargetRatio, 0, Notation::Fixed) << "x is "
     << (met == cells ? "met" : "not met") << " (" << met << " of " << cells << " cells). ";
  return os.str();
}

std::string otherSentences(const SpeedFacts& f) {
  std::ostringstream os;
  if (std::isfinite(f.slope_lo))
    os << "Its cost per fast period grows as N^" << range(f.slope_lo, f.slope_hi, "")
       << " from N = " << f.slope_n_lo << " to " << f.slope_n_hi << " (target N^"
       << benchNumber(kSlopeTargetLow, 1, Notation::Fixed) << "-"
       << benchNumber(kSlopeTargetHigh, 1, Notation::Fixed) << "). ";
  if (std::isfinite(f.default_wall))
    os << "The default rig (`metrosync run " << kDefaultRig << " --quiet --no-plot`) integrates in "
       << benchNumber(1e3 * f.default_wall, 3) << " ms (`wall_seconds`; "
       << benchNumber(1e3 * f.default_engine, 3)
       << " ms in the engine, `engine_seconds`), the whole "
       << "process takes " << benchNumber(1e3 * f.default_process, 3) << " ms. ";
  if (f.run_rows > 0)
    os << "`metrosync run` takes " << range(f.run_ratio_lo, f.run_ratio_hi)
       << " its engine's time (`wall_seconds` / `engine_seconds` in summary.json; target <= "
       << benchNumber(f.run_target, 2, Notation::Fixed) << ", met in " << f.run_met << " of "
       << f.run_rows << " scenes and variants"
       << (f.run_inconsistent > 0
               ? "; " + std::to_string(f.run_inconsistent) +
                     (f.run_inconsistent == 1 ? " run" : " runs") +
                     " reported an impossible split, engine_seconds <= 0 or above "
                     "wall_seconds, left out"
               : std::string())
       << "). ";
  if (std::isfinite(f.full_map_s) || std::isfinite(f.slow_map_s)) {
    os << "On 2 cores ";
    if (std::isfinite(f.full_map_s))
      os << "the 64 x 64 full-model map takes " << benchNumber(f.full_map_s, 3) << " s (target "
         << benchNumber(f.full_target_s, 6) << " s)";
    if (std::isfinite(f.full_map_s) && std::isfinite(f.slow_map_s)) os << " and ";
    if (std::isfinite(f.slow_map_s))
      os << "the 100 x 100 slow-flow map " << benchNumber(f.slow_map_s, 3) << " s (target "
         << benchNumber(f.slow_target_s, 6) << " s)";
    os << ".";
  } else {
    os << "The maps were not timed in this run.";
  }
  return os.str();
}

// Above this 1-minute load the 2-core machine was shared with other work during the timings.
constexpr double kBusyLoad = 2.0;

std::string loadSentence(const SpeedFacts& f) {
  if (!(f.load_hi > kBusyLoad)) return "";
  return " The machine was busy (1-minute load up to " +
         benchNumber(f.load_hi, 1, Notation::Fixed) +
         " on 2 cores): the wall times of `run` and of the maps carry the other sessions' work; "
         "the ratios at equal error are CPU medians, which carry much less of it.";
}

}  // namespace

SpeedInputs readSpeedInputs(const std::string& dir) {
  const std::filesystem::path d(dir);
  SpeedInputs in;
  in.ratios_csv = slurp(d / "ratios.csv");
  in.nslope_csv = slurp(d / "nslope.csv");
  in.verdicts_md = slurp(d / "verdicts.md");
  in.run_csv = slurp(d / "run.csv");
  in.maps_csv = slurp(d / "maps.csv");
  in.run_md = slurp(d / "run.md");
  if (std::filesystem::is_directory(d))
    for (const auto& e : std::filesystem::directory_iterator(d)) {
      const std::string name = e.path().filename().string();
      if (name.rfind("wp-", 0) == 0 && name.size() > 4 &&
          name.compare(name.size() - 4, 4, ".csv") == 0 &&
          name.find("-equal-error.csv") == std::string::npos)
        in.wp_csvs.push_back(slurp(e.path()));
    }
  in.maps_md = slurp(d / "maps.md");
  in.provenance_md = slurp(d / "provenance.md");
  return in;
}

SpeedFacts speedFacts(const SpeedInputs& in) {
  SpeedFacts f;
  f.err_lo = f.err_hi = f.slope_lo = f.slope_hi = kNaN;
  f.run_ratio_lo = f.run_ratio_hi = f.full_map_s = f.slow_map_s = kNaN;
  f.run_target = f.full_target_s = f.slow_target_s = kNaN;
  f.default_wall = f.default_engine = f.default_process = kNaN;
  f.load_lo = f.load_hi = kNaN;
  ratioFacts(parseCsv(in.ratios_csv, "ratios.csv"), f);
  slopeFacts(parseCsv(in.nslope_csv, "nslope.csv"), f);
  runFacts(parseCsv(in.run_csv, "run.csv"), f);
  mapFacts(parseCsv(in.maps_csv, "maps.csv"), f);
  for (const std::string& text : in.wp_csvs) {  // the work-precision points' loads
    const Csv c = parseCsv(text, "wp-*.csv");
    for (size_t r = 0; r < c.rows.size(); ++r) {
      if (c.number(r, "runs") <= 0) continue;
      widen(c.number(r, "load1_min"), f.load_lo, f.load_hi);
      widen(c.number(r, "load1_max"), f.load_lo, f.load_hi);
    }
  }
  return f;
}

std::string speedParagraph(const SpeedFacts& f, const SpeedInputs& in) {
  std::ostringstream os;
  os << "**Speed at equal error** ([" << in.folder << "/](" << in.folder
     << "/README.md): one run of `tools/bench/speed.sh`"
     << (in.date.empty() ? "" : " on " + in.date)
     << (in.commit.empty() ? "" : ", commit " + in.commit) << ", the project's 2-core machine"
     << (std::isfinite(f.load_lo)
             ? " at 1-minute load " + benchNumber(f.load_lo, 1, Notation::Fixed) + "-" +
                   benchNumber(f.load_hi, 1, Notation::Fixed)
             : std::string())
     << "). " << ratioSentence(f) << otherSentences(f) << loadSentence(f) << "\n";
  return os.str();
}

std::string speedPage(const SpeedFacts& f, const SpeedInputs& in) {
  std::ostringstream os;
  os << "# Speed at equal error against a careful C++ program (issue 23)\n\n"
     << "Everything in this folder comes from one run of `tools/bench/speed.sh`; README.md's "
        "speed paragraph is this one, rewritten by the same run.\n\n"
     << speedParagraph(f, in) << "\n";
  if (!in.provenance_md.empty()) os << "## How it was made\n\n" << in.provenance_md << "\n";
  os << "## The verdicts against the careful peer\n\n"
     << (in.verdicts_md.empty() ? "Not measured in this run (the peer was missing).\n"
                                : in.verdicts_md)
     << "\nEvery table, the wall-time tables, the reason of each empty cell and the peer's "
        "validation: [ratios.md](ratios.md); every point: `wp-<scene>.md` and `.csv`.\n\n";
  if (!in.run_md.empty()) os << "## `run` against its engine\n\n" << in.run_md << "\n";
  if (!in.maps_md.empty()) os << "## The maps\n\n" << in.maps_md << "\n";
  os << "## Files\n\n"
     << "- `provenance.md`: when, on what, and the commands (quoted above);\n"
     << "- `verdicts.md`: the headline verdicts and tables (quoted above); `ratios.md`: every "
        "ratio table (CPU and wall), the reasons of the empty cells, the validation; "
        "`ratios.csv`, `nslope.csv`: every cell and every point of the N-slope;\n"
     << "- `wp-<scene>.md`, `.csv`, `.png`: every measured point of every scene (errors, CPU "
        "and wall medians with and without samples, steps, evaluations, events); "
        "`wp-<scene>-equal-error.csv`: the engines' ratios on each scene;\n"
     << "- `run.md`, `run.csv`: `run` against its engine; `maps.md`, `maps.csv`: the maps.\n";
  return os.str();
}

std::string replaceBetweenMarkers(const std::string& text, const std::string& begin,
                                  const std::string& end, const std::string& block) {
  const size_t b = text.find(begin), e = text.find(end);
  if (b == std::string::npos || e == std::string::npos)
    throw std::invalid_argument("no '" + (b == std::string::npos ? begin : end) +
                                "' marker in the text");
  if (text.find(begin, b + 1) != std::string::npos || text.find(end, e + 1) != std::string::npos)
    throw std::invalid_argument("a marker appears twice ('" + begin + "', '" + end + "')");
  if (e < b) throw std::invalid_argument("the '" + end + "' marker comes before '" + begin + "'");
  const size_t after_begin = text.find('\n', b);
  const size_t end_line = text.rfind('\n', e);
  if (after_begin == std::string::npos || end_line == std::string::npos || end_line < after_begin)
    throw std::invalid_argument("the markers must be on lines of their own");
  std::string body = block;
  if (!body.empty() && body.back() != '\n') body += '\n';
  return text.substr(0, after_begin + 1) + body + text.substr(end_line + 1);
}

}  // namespace metrosync::bench
