#include "tools/bench/peer_verdict_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "base/number_text.h"
#include "tools/bench/bench_metrics.h"

namespace metrosync::bench {

namespace {

// "33.2 us", "1.09 ms", "2.5 s"
std::string duration(double s) {
  if (!std::isfinite(s)) return "";
  if (s < 1e-3) return benchNumber(s * 1e6, 3) + " us";
  if (s < 1) return benchNumber(s * 1e3, 3) + " ms";
  return benchNumber(s, 3) + " s";
}

std::string joined(const std::vector<std::string>& v, const std::string& sep) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

// The command as a shell block: lines of at most ~92 characters joined by backslashes, never
// breaking a single-quoted argument.
std::string wrapCommand(const std::string& cmd) {
  std::vector<std::string> words(1);
  bool quoted = false;
  for (char c : cmd) {
    if (c == '\'') quoted = !quoted;
    if (c == ' ' && !quoted) {
      if (!words.back().empty()) words.emplace_back();
    } else {
      words.back() += c;
    }
  }
  std::string out, line;
  for (const std::string& w : words) {
    if (!line.empty() && line.size() + 1 + w.size() > 92) {
      out += line + " \\\n        ";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + w;
  }
  return out + line;
}

std::string methodsOf(const std::vector<VerdictScene>& scenes, bool ours) {
  std::vector<std::string> all;
  for (const VerdictScene& s : scenes)
    for (const std::string& m : ours ? s.our_methods : s.peer_methods)
      if (std::find(all.begin(), all.end(), m) == all.end()) all.push_back(m);
  return joined(all, ", ");
}

std::string loadRange(const std::vector<VerdictScene>& scenes) {
  double lo = NAN, hi = NAN;
  for (const VerdictScene& s : scenes)
    lo = std::fmin(lo, s.load_min), hi = std::fmax(hi, s.load_max);
  return std::isfinite(lo)
             ? benchNumber(lo, 2, Notation::Fixed) + " ... " + benchNumber(hi, 2, Notation::Fixed)
             : "not recorded";
}

std::string slopeCsvRows(const std::vector<SlopeRow>& rows, ErrorMeasure m, Clock c) {
  std::string s;
  for (const SlopeRow& r : rows)
    for (int side = 0; side < 2; ++side)
      for (size_t k = 0; k < r.ns.size(); ++k)
        s += measureName(m) + "," + clockName(c) + "," + benchNumber(r.error, 6) + "," +
             (side == 0 ? "metrosync" : "peer") + "," + csvField(r.scenes[k]) + "," +
             std::to_string(r.ns[k]) + "," +
             benchNumber((side == 0 ? r.ours_per_period_s : r.peer_per_period_s)[k], 6) + "," +
             benchNumber(side == 0 ? r.slope_ours : r.slope_peer, 4) + "\n";
  return s;
}

std::string slopeMarkdown(const std::vector<SlopeRow>& rows, ErrorMeasure m, Clock c) {
  std::ostringstream os;
  if (rows.empty()) return "No N-scaling scene in this run.\n";
  os << "Cost per fast period at equal " << measureName(m) << " error (" << clockName(c)
     << " time of the run / fast periods; metrosync, the peer in parentheses) and the "
     << "least-squares slope of log(time per period) against log N (linear in N: slope 1):\n\n"
     << "| error |";
  for (size_t k = 0; k < rows[0].ns.size(); ++k)
    os << " " << rows[0].scenes[k] << " (N = " << rows[0].ns[k] << ") |";
  os << " slope metrosync | slope peer |\n|---|";
  for (size_t k = 0; k < rows[0].ns.size() + 2; ++k) os << "---|";
  os << "\n";
  for (const SlopeRow& r : rows) {
    os << "| " << errorLabel(r.error) << " |";
    for (size_t k = 0; k < r.ns.size(); ++k) {
      const double o = r.ours_per_period_s[k], p = r.peer_per_period_s[k];
      os << " " << (std::isfinite(o) ? duration(o) : "not reached")
         << (std::isfinite(p)            ? " (" + duration(p) + ")"
             : r.peer_skipped[k].empty() ? std::string(" (peer: not reached)")
                                         : std::string(" (peer: not run)"))
         << " |";
    }
    os << " "
       << (std::isfinite(r.slope_ours) ? benchNumber(r.slope_ours, 2, Notation::Fixed) : "n/a")
       << " | "
       << (std::isfinite(r.slope_peer) ? benchNumber(r.slope_peer, 2, Notation::Fixed) : "n/a")
       << " |\n";
  }
  os << "\nA cell reads \"not reached\" where the side's front does not cover that error on that "
        "scene (\"not run\": the peer cannot run the scene); the slope is fitted over the scenes "
        "that do. Target for metrosync (issue 23): slope "
     << benchNumber(kSlopeTargetLow, 1, Notation::Fixed) << " ... "
     << benchNumber(kSlopeTargetHigh, 1, Notation::Fixed) << ".\n";
  return os.str();
}

std::string agreementMarkdown(const std::vector<Agreement>& ag, const Sides& sides) {
  std::ostringstream os;
  const double bound = ag.empty() ? kPeerAgreement : ag.front().bound;
  os << "The peer validated against metrosync at tight tolerance (a `--cross-check` of one side "
        "against the other side's reference). Bound: final-state difference <= "
     << benchNumber(bound, 0, Notation::Scientific) << " ("
     << benchNumber(kPeerAgreement, 0, Notation::Scientific) << ", or "
     << benchNumber(kAgreementMargin, 0, Notation::Fixed)
     << " times below the smallest error of the ratio tables if that is tighter: far below the "
        "errors compared):\n\n"
     << "| scene | reference | cross-check | final-state difference | envelope difference | |\n"
     << "|---|---|---|---|---|---|\n";
  for (const Agreement& a : ag) {
    os << "| " << a.scene << " | " << a.reference << " | ";
    if (!a.skipped.empty()) {
      os << " |  |  | the peer was not run: " << a.skipped << " |\n";
      continue;
    }
    if (!a.validated && !a.self) {
      os << " |  |  | **not validated**: no cross-check of " << sides.peer << " against "
         << sides.ours << " (add `--cross-check " << sides.peer << ":rkf78:1e-13`) |\n";
      continue;
    }
    os << a.check << " | " << benchNumber(a.err_final, 1, Notation::Scientific) << " | "
       << benchNumber(a.err_envelope, 1, Notation::Scientific) << " | "
       << (a.self        ? std::string("the reference's own uncertainty (same engine)")
           : a.flagged() ? "**FLAG: above " + benchNumber(a.bound, 0, Notation::Scientific) + "**"
                         : "agrees (<= " + benchNumber(a.bound, 0, Notation::Scientific) + ")")
       << " |\n";
  }
  return os.str();
}

std::string headerMarkdown(const std::vector<VerdictScene>& scenes, const VerdictOptions& o) {
  std::ostringstream os;
  os << "# metrosync against the peer at equal error (issues 11 and 23)\n\n"
     << "ratio = peer time / metrosync time to reach the same error (> 1: metrosync is faster; "
     << "the issue's target is >= " << benchNumber(kTargetRatio, 1, Notation::Fixed)
     << ", **bold**: below it). "
     << "Each side's front is its cheapest run at each error over all its integrators "
     << "(metrosync: " << methodsOf(scenes, true) << "; the peer: " << methodsOf(scenes, false)
     << "), interpolated linearly in log(time) against log(error) between measured points and "
     << "never extrapolated: a cell is empty where a side's points do not bracket the error (the "
     << "reasons follow each table). Times are medians of " << fewestRuns(scenes)
     << " or more runs per point, of the CPU time (the headline: the machine is shared, and the "
     << "CPU time of these single-threaded runs carries much less of the other sessions' "
     << "preemption than the wall time) and of the wall time. At equal final-state error both "
     << "sides do the same work: integration and events, no samples (metrosync's runs with a "
     << "sink that declines the trajectory and the envelope; the careful peer's own --repeat "
     << "medians inside its process). 1-minute load during the timed runs: " << loadRange(scenes)
     << ".\n\n";
  if (!o.command.empty()) os << "Made by:\n\n    " << wrapCommand(o.command) << "\n\n";
  return os.str();
}

}  // namespace

std::string verdictLine(const RatioTable& t, const Verdict& v) {
  std::ostringstream os;
  const auto compared = std::count_if(t.rows.begin(), t.rows.end(),
                                      [](const RatioRow& r) { return r.skipped.empty(); });
  os << "Verdict at equal " << measureName(t.measure) << " error (" << clockName(t.clock)
     << " medians, target >= " << benchNumber(kTargetRatio, 1, Notation::Fixed) << " from "
     << (t.errors.empty() ? "" : errorLabel(t.errors.front())) << " to "
     << (t.errors.empty() ? "" : errorLabel(t.errors.back())) << " on " << compared << " scenes): ";
  if (v.met) return os.str() + "MET in all " + std::to_string(v.cells) + " cells.";
  os << "NOT MET";
  if (v.cells == 0) return os.str() + " (no scene has points on both sides).";
  os << ": below " << benchNumber(kTargetRatio, 1, Notation::Fixed) << " in " << v.below << " of "
     << v.cells << " cells";
  if (std::isfinite(v.worst))
    os << " (worst " << benchNumber(v.worst, 2, Notation::Fixed) << ", " << v.worst_at << ")";
  if (!v.below_where.empty()) os << " at " << joined(v.below_where, "; ");
  if (v.empty > 0)
    os << (v.below ? "; " : ", ") << v.empty << " not measured on both sides at "
       << joined(v.empty_where, "; ");
  return os.str() + ".";
}

std::string ratioTableMarkdown(const RatioTable& t) {
  std::ostringstream os;
  os << "| scene | N |";
  for (double e : t.errors) os << " " << errorLabel(e) << " |";
  os << "\n|---|---|";
  for (size_t k = 0; k < t.errors.size(); ++k) os << "---|";
  os << "\n";
  std::vector<std::string> reasons;
  for (const RatioRow& row : t.rows) {
    os << "| " << row.scene << " | " << row.n << " |";
    if (!row.skipped.empty()) {  // the reason in the first cell, the others empty
      os << " peer not run: " << row.skipped << " |";
      for (size_t k = 1; k < row.cells.size(); ++k) os << "  |";
      os << "\n";
      continue;
    }
    // the reasons of this row's empty cells, each once with the errors it explains
    std::vector<std::pair<std::string, std::string>> why;
    for (const RatioCell& c : row.cells) {
      if (c.filled()) {
        const std::string r = benchNumber(c.ratio, 2, Notation::Fixed);
        os << " " << (c.ratio < kTargetRatio ? "**" + r + "**" : r) << " |";
        continue;
      }
      os << "  |";
      auto it =
          std::find_if(why.begin(), why.end(), [&](const auto& w) { return w.first == c.reason; });
      if (it == why.end())
        why.push_back({c.reason, errorLabel(c.error)});
      else
        it->second += ", " + errorLabel(c.error);
    }
    os << "\n";
    for (const auto& [reason, errs] : why)
      reasons.push_back("- " + row.scene + ", " + errs + ": " + reason);
  }
  if (!reasons.empty()) os << "\nEmpty cells:\n\n" << joined(reasons, "\n") << "\n";
  return os.str();
}

std::string ratiosCsvRows(const RatioTable& t, const std::string& side) {
  std::string s;
  for (const RatioRow& row : t.rows)
    for (const RatioCell& c : row.cells)
      s += measureName(t.measure) + "," + clockName(t.clock) + "," + csvField(row.scene) + "," +
           std::to_string(row.n) + "," + benchNumber(c.error, 6) + "," +
           benchNumber(c.time_ours_s, 6) + "," + benchNumber(c.time_peer_s, 6) + "," +
           benchNumber(c.ratio, 6) + "," +
           (c.filled() ? (c.ratio < kTargetRatio ? "1" : "0") : "") + "," + csvField(c.reason) +
           "," + side + "\n";
  return s;
}

std::string sceneVerdictLine(const RatioRow& row) {
  std::ostringstream os;
  os << row.scene << " (N = " << row.n << "): ";
  if (!row.skipped.empty()) return os.str() + "the peer was not run (" + row.skipped + ").";
  const Verdict v = verdictOf(row);
  double lo = NAN, hi = NAN;
  for (const RatioCell& c : row.cells)
    if (c.filled()) lo = std::fmin(lo, c.ratio), hi = std::fmax(hi, c.ratio);
  const std::string a = benchNumber(lo, 2, Notation::Fixed),
                    b = benchNumber(hi, 2, Notation::Fixed);
  const std::string range = !std::isfinite(lo) ? "no cell" : (a == b ? a : a + "-" + b) + "x";
  if (v.met) return os.str() + "MET, " + range + " in all " + std::to_string(v.cells) + " cells.";
  os << "NOT MET, " << range;
  // the row's own "scene: errors" entries, without the scene
  const auto where = [&](const std::vector<std::string>& w) {
    return w.empty() ? std::string() : w.front().substr(row.scene.size() + 2);
  };
  if (v.below)
    os << "; below " << benchNumber(kTargetRatio, 1, Notation::Fixed) << " at "
       << where(v.below_where);
  if (v.empty) os << "; not measured on both sides at " << where(v.empty_where);
  return os.str() + ".";
}

namespace {

// metrosync's N-slope at each error, against issue 23's target.
std::vector<std::string> slopeLines(const std::vector<SlopeRow>& rows, ErrorMeasure m) {
  std::vector<std::string> out;
  for (const SlopeRow& r : rows) {
    std::string s = "N-slope of metrosync's cost per fast period at equal " + measureName(m) +
                    " error " + errorLabel(r.error) + ": ";
    if (!std::isfinite(r.slope_ours)) {
      out.push_back(s + "n/a (fewer than two scenes reach it).");
      continue;
    }
    const bool met = r.slope_ours <= kSlopeTargetHigh;
    int used = 0;
    for (double t : r.ours_per_period_s) used += std::isfinite(t) ? 1 : 0;
    out.push_back(
        s + "N^" + benchNumber(r.slope_ours, 2, Notation::Fixed) + " over " + std::to_string(used) +
        " scenes (N = " + std::to_string(r.ns.front()) + " ... " + std::to_string(r.ns.back()) +
        "), target " + benchNumber(kSlopeTargetLow, 1, Notation::Fixed) + "-" +
        benchNumber(kSlopeTargetHigh, 1, Notation::Fixed) + ": " + (met ? "met." : "NOT met."));
  }
  return out;
}

// The guards that failed, one line each.
std::vector<std::string> guardWarnings(const std::vector<VerdictScene>& scenes,
                                       const std::vector<Agreement>& ag) {
  std::vector<std::string> w;
  const int runs = fewestRuns(scenes);
  if (runs < kMinRunsForResult)
    w.push_back("medians of as few as " + std::to_string(runs) + " runs (fewer than " +
                std::to_string(kMinRunsForResult) +
                "): the ratio table is not a result; rerun with --repeat " +
                std::to_string(kMinRunsForResult) + " or more");
  for (const Agreement& a : ag) {
    if (!a.flagged()) continue;  // self-checks and skipped scenes never are
    std::string line = a.scene + ": ";
    if (!a.validated) {
      w.push_back(line + "the peer is not validated (no cross-check against metrosync)");
      continue;
    }
    line += "the peer's cross-check " + a.check + " differs from the reference " + a.reference +
            " by " + benchNumber(a.err_final, 1, Notation::Scientific) + " in final state (> " +
            benchNumber(a.bound, 0, Notation::Scientific) + ")";
    for (const Agreement& b : ag)
      if (b.self && b.scene == a.scene)
        line += "; the reference's own engine differs from it by " +
                benchNumber(b.err_final, 1, Notation::Scientific) + " (" + b.check + ")";
    w.push_back(line);
  }
  return w;
}

std::string cellText(const RatioCell& c) {
  if (!c.filled()) return "-";
  const std::string r = benchNumber(c.ratio, 2, Notation::Fixed);
  return c.ratio < kTargetRatio ? "**" + r + "**" : r;
}

// Each scene's engine / peer and run / peer cells side by side (wall time).
std::string sideBySide(const RatioTable& engine, const RatioTable& run) {
  std::ostringstream os;
  os << "| scene | N |";
  for (double e : run.errors) os << " " << errorLabel(e) << " |";
  os << "\n|---|---|";
  for (size_t k = 0; k < run.errors.size(); ++k) os << "---|";
  os << "\n";
  for (const RatioRow& r : run.rows) {
    const auto e = std::find_if(engine.rows.begin(), engine.rows.end(),
                                [&](const RatioRow& x) { return x.scene == r.scene; });
    os << "| " << r.scene << " | " << r.n << " |";
    for (size_t k = 0; k < r.cells.size(); ++k)
      os << " " << (e == engine.rows.end() ? "-" : cellText(e->cells[k])) << " / "
         << cellText(r.cells[k]) << " |";
    os << "\n";
  }
  return os.str();
}

}  // namespace

RunVerdictText runVerdict(const std::vector<VerdictScene>& scenes,
                          const std::vector<double>& errors) {
  RunVerdictText v;
  const std::vector<VerdictScene> run_scenes = runAsOurs(scenes);
  if (run_scenes.empty()) return v;
  std::vector<VerdictScene> engine_scenes;  // the same scenes, the engine's side
  for (const VerdictScene& s : scenes)
    if (!s.run.empty()) engine_scenes.push_back(s);
  const RatioTable run = ratioTable(run_scenes, ErrorMeasure::FinalState, Clock::Wall, errors);
  const RatioTable engine =
      ratioTable(engine_scenes, ErrorMeasure::FinalState, Clock::Wall, errors);
  v.line = "`metrosync run`: " + verdictLine(run, verdictOf(run));
  v.csv_rows = ratiosCsvRows(run, "run");
  std::ostringstream md;
  md << "**" << v.line << "**\n\n";
  for (const RatioRow& row : run.rows) md << "- `run` on " << sceneVerdictLine(row) << "\n";
  md << "\nratio = peer time / metrosync time at equal final-state error, wall clock (the "
        "peer's wall median inside its process; the engine's runs without samples; `run`'s "
        "summary.json wall_seconds): engine / `run` in each cell (**bold**: below "
     << benchNumber(kTargetRatio, 1, Notation::Fixed) << "; -: not measured on both sides).\n\n"
     << sideBySide(engine, run) << "\n`run` / peer alone, with the reasons of its empty cells:\n\n"
     << ratioTableMarkdown(run) << "\n### `run` against its engine at each point\n\n"
     << runPointsMarkdown(runOverheads(scenes));
  v.markdown = md.str();
  return v;
}

VerdictPages verdictPages(const std::vector<VerdictScene>& scenes, const VerdictOptions& o) {
  VerdictPages p;
  const std::vector<Agreement> ag = peerAgreement(scenes, o.sides, agreementBound(o.errors));
  p.warnings = guardWarnings(scenes, ag);
  p.ratios_csv =
      "measure,clock,scene,n,error,time_metrosync_s,time_peer_s,ratio,below_target,reason,side\n";
  p.slope_csv = "measure,clock,error,side,scene,n,time_per_period_s,slope\n";
  std::ostringstream body;
  for (ErrorMeasure m : {ErrorMeasure::FinalState, ErrorMeasure::Envelope}) {
    const bool headline_measure = m == ErrorMeasure::FinalState;
    if (!headline_measure && !peerMeasured(scenes, m)) {
      body << "## Equal " << measureName(m) << " error\n\nNot compared: the peer (" << o.sides.peer
           << ") reports no " << measureName(m) << " error.\n\n";
      continue;
    }
    for (Clock c : {Clock::Cpu, Clock::Wall}) {
      const RatioTable t = ratioTable(scenes, m, c, o.errors);
      const bool headline = headline_measure && c == Clock::Cpu;
      const std::string line = verdictLine(t, verdictOf(t));
      body << "## Equal " << measureName(m) << " error, " << clockName(c) << " time"
           << (headline ? " (the headline)" : "") << "\n\n"
           << line << "\n\n";
      std::ostringstream lines;
      if (headline) {
        p.verdict_line = line;
        for (const RatioRow& row : t.rows) p.scene_lines.push_back(sceneVerdictLine(row));
        for (const std::string& l : p.scene_lines) lines << "- " << l << "\n";
        body << lines.str() << "\n";
      }
      body << ratioTableMarkdown(t) << "\n";
      p.ratios_csv += ratiosCsvRows(t, "engine");
      const auto slope = nSlope(scenes, o.slope_scenes, o.slope_errors, m, c);
      p.slope_csv += slopeCsvRows(slope, m, c);
      if (headline) {
        p.slope_lines = slopeLines(slope, m);
        std::ostringstream v;
        // issue 36 drops the N-slope's target: ratios.md keeps the slope, verdicts.md does not
        v << "**" << line << "**\n\n"
          << lines.str() << "\n"
          << ratioTableMarkdown(t) << "\n"
          << agreementMarkdown(ag, o.sides);
        p.verdicts_markdown = v.str();
      }
      if (c == Clock::Cpu)
        body << "### Cost per fast period against N (" << measureName(m) << " error)\n\n"
             << slopeMarkdown(slope, m, c) << "\n";
    }
  }
  const RunVerdictText run = runVerdict(scenes, o.errors);
  p.ratios_csv += run.csv_rows;
  p.run_verdict_line = run.line;
  if (!run.markdown.empty()) {
    const std::string section = "## `metrosync run` against the peer\n\n" + run.markdown + "\n";
    body << section;
    p.verdicts_markdown = section + "## The engine against the peer\n\n" + p.verdicts_markdown;
  }
  std::ostringstream md;
  md << headerMarkdown(scenes, o) << "**" << p.verdict_line << "**\n\n";
  if (!run.line.empty()) md << "**" << run.line << "**\n\n";
  for (const std::string& w : p.warnings) md << "**Warning: " << w << ".**\n\n";
  for (const std::string& l : p.slope_lines) md << l << "\n\n";
  md << body.str() << "## Validation of the peer\n\n" << agreementMarkdown(ag, o.sides);
  p.markdown = md.str();
  return p;
}

}  // namespace metrosync::bench
