#include "tools/bench/speed_figures.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "tools/bench/bench_metrics.h"
#include "tools/bench/csv_table.h"
#include "tools/bench/peer_verdict.h"
#include "tools/bench/speed_targets.h"

namespace metrosync::bench {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string fixed2(double v) {
  return benchNumber(v, 2, Notation::Fixed);
}

// a ratio as the table prints it: two decimals, none from 100 on
std::string times(double v) {
  return benchNumber(v, std::abs(v) >= 100 ? 0 : 2, Notation::Fixed);
}

std::string range(double lo, double hi, const std::string& unit) {
  const std::string a = fixed2(lo), b = fixed2(hi);
  return (a == b ? a : a + "-" + b) + unit;
}

SpeedFigure notMeasured(const std::string& what, const std::string& target) {
  return {what, "not measured in this run", target, "not measured", ""};
}

// The cells of ratios.csv (final-state error) of one side and clock, of `scene` ("" = every
// scene the peer ran).
struct Cells {
  int cells = 0, filled = 0, below = 0;
  double lo = kNaN, hi = kNaN, e_lo = kNaN, e_hi = kNaN;
  std::string worst_at;
};

Cells ratioCells(const CsvTable& c, const std::string& side, const std::string& clock,
                 const std::string& scene) {
  Cells k;
  for (size_t r = 0; r < c.rows.size(); ++r) {
    if (c.text(r, "measure") != "final-state" || c.text(r, "clock") != clock) continue;
    if (c.textOr(r, "side", "engine") != side) continue;
    if (c.text(r, "reason").rfind(kPeerNotRun, 0) == 0) continue;
    if (!scene.empty() && c.text(r, "scene") != scene) continue;
    ++k.cells;
    const double v = c.number(r, "ratio"), e = c.number(r, "error");
    k.e_lo = std::fmin(k.e_lo, e), k.e_hi = std::fmax(k.e_hi, e);
    if (!std::isfinite(v)) continue;
    ++k.filled, k.below += v < kTargetRatio;
    if (!(v >= k.lo)) k.worst_at = c.text(r, "scene") + " at " + errorLabel(e);
    k.lo = std::fmin(k.lo, v), k.hi = std::fmax(k.hi, v);
  }
  return k;
}

SpeedFigure peerFigure(const CsvTable& c, const std::string& what, const std::string& side,
                       const std::string& clock, const std::string& scene) {
  const std::string target =
      ">= " + benchNumber(kTargetRatio, 1, Notation::Fixed) + "x the peer's speed at every error";
  const Cells k = ratioCells(c, side, clock, scene);
  if (k.cells == 0) return notMeasured(what, target);
  SpeedFigure f{what, "", target, "", ""};
  f.measured = (k.filled ? range(k.lo, k.hi, "x") : "no cell") + " (" + std::to_string(k.filled) +
               " of " + std::to_string(k.cells) + " cells, errors " + errorLabel(k.e_hi) + " to " +
               errorLabel(k.e_lo) + ")";
  const bool met = k.filled == k.cells && k.below == 0;
  f.verdict = met ? "met" : "NOT met";
  if (met) return f;
  if (k.below)
    f.by = "worst " + fixed2(k.lo) + "x (" + k.worst_at + "): " + fixed2(kTargetRatio / k.lo) +
           "x short; below the target in " + std::to_string(k.below) + " of " +
           std::to_string(k.filled) + " cells";
  if (k.filled < k.cells)
    f.by += (f.by.empty() ? "" : "; ") + std::to_string(k.cells - k.filled) +
            (k.cells - k.filled == 1 ? " cell" : " cells") + " not measured on both sides";
  return f;
}

// The largest of `values` (named by `where`) against an upper bound.
SpeedFigure upperFigure(const std::string& what, const std::vector<double>& values,
                        const std::vector<std::string>& where, double bound,
                        const std::string& detail = "") {
  const std::string target = "<= " + fixed2(bound) + "x";
  double lo = kNaN, hi = kNaN;
  std::string at;
  for (size_t k = 0; k < values.size(); ++k) {
    if (!std::isfinite(values[k])) continue;
    if (!(values[k] <= hi)) at = where[k];
    lo = std::fmin(lo, values[k]), hi = std::fmax(hi, values[k]);
  }
  if (!std::isfinite(hi)) return notMeasured(what, target);
  SpeedFigure f{what, range(lo, hi, "x") + detail, target, hi <= bound ? "met" : "NOT met", ""};
  if (hi > bound) f.by = "worst " + fixed2(hi) + "x (" + at + "): " + fixed2(hi / bound) + "x over";
  return f;
}

// The figures of `run` against its engine: at the points of the work-precision (runpoints.csv),
// on every bench scene and on the default rig (run.csv).
void runFigures(const SpeedInputs& in, std::vector<SpeedFigure>& out) {
  const CsvTable p = parseCsvTable(in.runpoints_csv, "runpoints.csv");
  std::vector<double> over_engine, over_alone;
  std::vector<std::string> where;
  for (size_t r = 0; r < p.rows.size(); ++r) {
    over_engine.push_back(p.number(r, "wall_over_engine"));
    over_alone.push_back(p.number(r, "wall_over_alone"));
    where.push_back(p.text(r, "scene") + " " + p.text(r, "method"));
  }
  out.push_back(upperFigure("`wall_seconds / engine_seconds` on those runs", over_engine, where,
                            kRunOverEngineTarget));
  out.push_back(upperFigure("`run`'s wall_seconds / the engine with recording off, same runs",
                            over_alone, where, kRunOverEngineTarget));
  const CsvTable c = parseCsvTable(in.run_csv, "run.csv");
  std::vector<double> alone;
  std::vector<std::string> scenes;
  SpeedFigure def =
      notMeasured("default rig (`metrosync run --no-plot`): wall against engine", "<= 1.15x");
  for (size_t r = 0; r < c.rows.size(); ++r) {
    if (!c.text(r, "failure").empty() || !c.text(r, "variant").empty()) continue;
    const std::string scene = c.text(r, "scene");
    const double a = c.has("wall_over_alone") ? c.number(r, "wall_over_alone") : kNaN;
    if (scene != kDefaultRig && scene != kDefaultRigFile) {
      alone.push_back(a), scenes.push_back(scene);
      continue;
    }
    const double ratio = c.number(r, "ratio");
    def = upperFigure(def.what, {ratio, a},
                      {"wall_seconds / engine_seconds", "over the engine alone"},
                      kRunOverEngineTarget);
    def.measured = "wall_seconds " + benchNumber(1e3 * c.number(r, "wall_seconds"), 3) +
                   " ms, engine_seconds " + benchNumber(1e3 * c.number(r, "engine_seconds"), 3) +
                   " ms: " + fixed2(ratio) +
                   (c.has("ratio_min")
                        ? "x (" + range(c.number(r, "ratio_min"), c.number(r, "ratio_max"), "x") +
                              " over " + c.text(r, "runs") + " runs)"
                        : "x") +
                   (std::isfinite(a) ? "; over the engine alone " + fixed2(a) + "x" : "");
  }
  out.push_back(upperFigure(
      "`run`'s wall_seconds / the engine with recording off, every bench scene, default sampling",
      alone, scenes, kRunOverEngineTarget, " over " + std::to_string(alone.size()) + " scenes"));
  out.push_back(def);
}

SpeedFigure processFigure(const SpeedInputs& in) {
  const std::string what = "whole process vs `wall_seconds` (peer-n2, `--no-plot`)";
  const CsvTable c = parseCsvTable(in.process_csv, "process.csv");
  if (c.rows.empty()) return notMeasured(what, "<= 1.5 x wall_seconds + 3 ms");
  const double total = c.number(0, "total_ms"), budget = c.number(0, "budget_ms");
  SpeedFigure f{what,
                benchNumber(total, 3) + " ms vs wall_seconds " +
                    benchNumber(c.number(0, "wall_seconds_ms"), 3) + " ms",
                "<= 1.5 x wall_seconds + 3 ms = " + benchNumber(budget, 3) + " ms",
                total <= budget ? "met" : "NOT met", ""};
  if (total > budget)
    f.by = "over by " + benchNumber(total - budget, 3) + " ms (" + fixed2(total / budget) +
           "x the budget; where each millisecond goes: process.md)";
  return f;
}

SpeedFigure eventFigure(const SpeedInputs& in) {
  const std::string what = "cost per step and per event against one RHS evaluation";
  const std::string target = "none: reported (in place of the N-slope)";
  const CsvTable c = parseCsvTable(in.eventcost_csv, "eventcost.csv");
  std::ostringstream os;
  for (size_t r = 0; r < c.rows.size(); ++r) {
    if (!c.text(r, "failure").empty()) continue;
    os << (os.tellp() > 0 ? "; " : "") << "N = " << c.text(r, "n") << " ("
       << c.text(r, "integrator") << " "
       << benchNumber(c.number(r, "accuracy"), 0, Notation::Scientific) << "): a step "
       << benchNumber(c.number(r, "evals_per_step"), 3) << " evaluations, "
       << benchNumber(c.number(r, "step_in_rhs"), 3) << " RHS of time; an event "
       << benchNumber(c.number(r, "evals_per_event"), 3) << ", "
       << benchNumber(c.number(r, "event_in_rhs"), 3) << " RHS";
  }
  if (os.tellp() <= 0) return notMeasured(what, target);
  return {what, os.str(), target, "reported", ""};
}

void fitFigures(const SpeedInputs& in, std::vector<SpeedFigure>& out) {
  const std::string what = "one fit (fit bench: 5 keys, 30 s records)";
  const CsvTable c = parseCsvTable(in.fit_csv, "fit.csv");
  std::vector<double> wall, cpu, ratio;
  for (size_t r = 0; r < c.rows.size(); ++r) {
    if (c.text(r, "record").empty()) continue;  // the failure's line
    wall.push_back(c.number(r, "wall_s")), cpu.push_back(c.number(r, "cpu_s"));
    ratio.push_back(c.number(r, "fit_over_run"));
  }
  if (wall.empty()) {
    out.push_back(notMeasured(what, "<= 1 s wall per fit on 2 cores"));
    out.push_back(notMeasured("one fit against one `run` of the same rig", "<= 100x"));
    return;
  }
  const double w = median(wall), q = median(ratio);
  SpeedFigure f{what,
                "median " + benchNumber(w, 3) + " s wall, " + benchNumber(median(cpu), 3) +
                    " s CPU over " + std::to_string(wall.size()) + " records",
                "<= 1 s wall per fit on 2 cores", w <= kFitWallTargetS ? "met" : "NOT met", ""};
  if (w > kFitWallTargetS) f.by = fixed2(w / kFitWallTargetS) + "x over";
  out.push_back(f);
  SpeedFigure g{"one fit against one `run` of the same rig", "median " + times(q) + "x", "<= 100x",
                q <= kFitOverRunTarget ? "met" : "NOT met", ""};
  if (q > kFitOverRunTarget) g.by = fixed2(q / kFitOverRunTarget) + "x over";
  out.push_back(g);
}

void continueFigures(const SpeedInputs& in, std::vector<SpeedFigure>& out) {
  const CsvTable c = parseCsvTable(in.continuation_csv, "continuation.csv");
  if (c.rows.empty())
    out.push_back(notMeasured("`continue --all` at N = 32", "<= 20 s wall on 2 cores"));
  for (size_t r = 0; r < c.rows.size(); ++r) {
    const double w = c.number(r, "wall_s");
    const bool stopped = c.text(r, "timed_out") == "1";
    SpeedFigure f{"`continue --all` at N = 32, `" + c.text(r, "rig") + "`",
                  (stopped ? "> " : "") + benchNumber(w, 3) + " s wall" +
                      (stopped ? " (stopped: not finished)" : ""),
                  "<= 20 s wall on 2 cores", "", ""};
    if (!c.text(r, "failure").empty() && !stopped)
      f.verdict = "not measured", f.measured = "failed: " + c.text(r, "failure");
    else
      f.verdict = !stopped && w <= kContinueTargetS ? "met" : "NOT met";
    if (f.verdict == "NOT met")
      f.by = (stopped ? "more than " : "") + fixed2(w / kContinueTargetS) + "x over";
    out.push_back(f);
  }
}

}  // namespace

std::vector<SpeedFigure> speedFigures(const SpeedInputs& in) {
  std::vector<SpeedFigure> f;
  const CsvTable r = parseCsvTable(in.ratios_csv, "ratios.csv");
  f.push_back(peerFigure(r, "`run` vs the peer, N = 2 (peer-n2; wall)", "run", "wall", "peer-n2"));
  f.push_back(peerFigure(r, "`run` vs the peer, N = 8 (peer-n8; wall)", "run", "wall", "peer-n8"));
  f.push_back(peerFigure(r, "`run` vs the peer, suppression (wall)", "run", "wall", "suppression"));
  runFigures(in, f);
  f.push_back(processFigure(in));
  f.push_back(peerFigure(r, "engine alone vs the peer, every scene the peer runs (CPU medians)",
                         "engine", "CPU", ""));
  f.push_back(peerFigure(r, "engine alone vs the peer, every scene the peer runs (wall medians)",
                         "engine", "wall", ""));
  f.push_back(eventFigure(in));
  fitFigures(in, f);
  continueFigures(in, f);
  return f;
}

std::string figuresMarkdown(const std::vector<SpeedFigure>& figures) {
  int judged = 0, met = 0;
  for (const SpeedFigure& f : figures) judged += f.judged(), met += f.verdict == "met";
  std::ostringstream os;
  os << "**Issue 36's figures: " << met << " of " << judged << " targets met.**\n\n"
     << "| what | measured | target | verdict | where missed, by how much |\n"
     << "|---|---|---|---|---|\n";
  for (const SpeedFigure& f : figures)
    os << "| " << f.what << " | " << f.measured << " | " << f.target << " | "
       << (f.verdict == "NOT met" ? "**NOT met**" : f.verdict) << " | " << f.by << " |\n";
  return os.str();
}

}  // namespace metrosync::bench
