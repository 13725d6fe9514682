#include "tools/bench/speed_summary.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "base/number_text.h"
#include "tools/bench/bench_metrics.h"
#include "tools/bench/csv_table.h"
#include "tools/bench/peer_verdict.h"
#include "tools/bench/speed_figures.h"
#include "tools/bench/wp_csv.h"

namespace metrosync::bench {

const char* const kSpeedBegin = "<!-- speed:begin";
const char* const kSpeedEnd = "<!-- speed:end";

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void widen(double v, double& lo, double& hi) {
  if (!std::isfinite(v)) return;
  lo = std::fmin(lo, v);
  hi = std::fmax(hi, v);
}

// The headline cells (final-state error, CPU) grouped by N; the peer's skipped scenes left out.
void ratioFacts(const CsvTable& c, SpeedFacts& f) {
  std::map<int, SpeedFacts::Group> groups;
  std::vector<std::string> scenes;
  for (size_t r = 0; r < c.rows.size(); ++r) {
    if (c.text(r, "measure") != "final-state" || c.text(r, "clock") != "CPU") continue;
    if (c.text(r, "reason").rfind(kPeerNotRun, 0) == 0) continue;
    if (c.textOr(r, "side", "engine") != "engine") continue;  // `run`'s: speed_figures.h
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

void slopeFacts(const CsvTable& c, SpeedFacts& f) {
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

void runFacts(const CsvTable& c, SpeedFacts& f) {
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
    const std::string& scene = c.text(r, "scene");
    if ((scene == kDefaultRig || scene == kDefaultRigFile) && c.text(r, "variant").empty()) {
      f.default_wall = c.number(r, "wall_seconds");
      f.default_engine = c.number(r, "engine_seconds");
      f.default_process = c.number(r, "process_wall_s");
    }
  }
}

void mapFacts(const CsvTable& c, SpeedFacts& f) {
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

// The peer measured against, as speed.sh names it in peer.md (its source's hash, its binary).
std::string peerName(const SpeedInputs& in) {
  return in.peer.empty() ? std::string("the careful C++ peer (not part of this repository)")
                         : in.peer;
}

std::string ratioSentence(const SpeedFacts& f, const SpeedInputs& in) {
  if (f.groups.empty())
    return "The careful peer was not measured in this run (it was missing: see the folder's "
           "README), so there is no ratio at equal error. ";
  std::ostringstream os;
  os << "Against the careful peer " << peerName(in)
     << " (a C++17 program on Boost.Odeint, the project's independent peer, not part of this "
        "repository: dopri5 and Fehlberg 7(8), fixed-size state, the same equations and events), "
        "at equal final-state error from "
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
  os << " over " << f.scenes << " scenes: the target of "
     << benchNumber(kTargetRatio, 0, Notation::Fixed) << "x is "
     << (met == cells ? "met" : "not met") << " (" << met << " of " << cells << " cells). ";
  return os.str();
}

std::string otherSentences(const SpeedFacts& f) {
  std::ostringstream os;  // (issue 36 drops the N-slope's target: ratios.md keeps the slope)
  if (std::isfinite(f.default_wall))
    os << "The default rig (`metrosync run --quiet --no-plot`) integrates in "
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

// Every judged figure of issue 36, "what: measured (verdict, by how much)".
std::string figuresSentence(const std::vector<SpeedFigure>& figures) {
  int judged = 0, met = 0;
  std::string list;
  for (const SpeedFigure& g : figures) {
    if (!g.judged()) continue;
    ++judged, met += g.verdict == "met";
    list += std::string(list.empty() ? "" : "; ") + g.what + ": " + g.measured + " (" + g.verdict +
            ", target " + g.target + ")";
  }
  if (judged == 0) return "";
  return "Issue 36's targets: " + std::to_string(met) + " of " + std::to_string(judged) +
         " met (by how much each is missed: the folder's table) -- " + list + ". ";
}

}  // namespace

SpeedFacts speedFacts(const SpeedInputs& in) {
  SpeedFacts f;
  f.err_lo = f.err_hi = f.slope_lo = f.slope_hi = kNaN;
  f.run_ratio_lo = f.run_ratio_hi = f.full_map_s = f.slow_map_s = kNaN;
  f.run_target = f.full_target_s = f.slow_target_s = kNaN;
  f.default_wall = f.default_engine = f.default_process = kNaN;
  f.load_lo = f.load_hi = kNaN;
  ratioFacts(parseCsvTable(in.ratios_csv, "ratios.csv"), f);
  slopeFacts(parseCsvTable(in.nslope_csv, "nslope.csv"), f);
  runFacts(parseCsvTable(in.run_csv, "run.csv"), f);
  mapFacts(parseCsvTable(in.maps_csv, "maps.csv"), f);
  for (const std::string& text : in.wp_csvs) {  // the work-precision points' loads
    const CsvTable c = parseCsvTable(text, "wp-*.csv");
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
     << "). " << ratioSentence(f, in) << figuresSentence(speedFigures(in)) << otherSentences(f)
     << loadSentence(f) << "\n";
  return os.str();
}

std::string speedPage(const SpeedFacts& f, const SpeedInputs& in) {
  std::ostringstream os;
  os << "# Speed against a careful C++ program (issues 23 and 36)\n\n"
     << "Everything in this folder comes from one run of `tools/bench/speed.sh`; README.md's "
        "speed paragraph is this one, rewritten by the same run. The peer: "
     << peerName(in) << ".\n\n"
     << speedParagraph(f, in) << "\n## Every figure against its target\n\n"
     << figuresMarkdown(speedFigures(in)) << "\n";
  if (!in.provenance_md.empty()) os << "## How it was made\n\n" << in.provenance_md << "\n";
  os << "## The verdicts against the careful peer\n\n"
     << (in.verdicts_md.empty() ? "Not measured in this run (the peer was missing).\n"
                                : in.verdicts_md)
     << "\nEvery table, the wall-time tables, the reason of each empty cell and the peer's "
        "validation: [ratios.md](ratios.md); every point: `wp-<scene>.md` and `.csv`.\n\n";
  if (!in.run_md.empty()) os << "## `run` against its engine\n\n" << in.run_md << "\n";
  const std::pair<const char*, const std::string*> parts[] = {
      {"The whole process, phase by phase", &in.process_md},
      {"Cost per step and per event", &in.eventcost_md},
      {"One fit", &in.fit_md},
      {"`continue --all` at N = 32", &in.continuation_md},
      {"The maps", &in.maps_md}};
  for (const auto& [title, md] : parts)
    if (!md->empty()) os << "## " << title << "\n\n" << *md << "\n";
  os << "## Files\n\n"
     << "- `provenance.md`: when, on what, and the commands (quoted above);\n"
     << "- `verdicts.md`: the headline verdicts and tables (quoted above); `ratios.md`: every "
        "ratio table (CPU and wall), the reasons of the empty cells, the validation; "
        "`ratios.csv`, `nslope.csv`: every cell and every point of the N-slope;\n"
     << "- `wp-<scene>.md`, `.csv`, `.png`: every measured point of every scene (errors, CPU "
        "and wall medians with and without samples, steps, evaluations, events); "
        "`wp-<scene>-equal-error.csv`: the engines' ratios on each scene;\n"
     << "- `runpoints.csv`: `run` against its engine at each point of the work-precision;\n"
     << "- `run.md`, `run.csv`: `run` against its engine on every scene; `process.md`, "
        "`process.csv`: the whole process; `eventcost.md`, `.csv`: cost per step and per event; "
        "`fit.md`, `.csv`: one fit; `continuation.md`, `.csv`: `continue --all`; `maps.md`, "
        "`maps.csv`: the maps; `peer.md`: the peer measured against.\n";
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
