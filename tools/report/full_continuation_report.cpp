#include "tools/report/full_continuation_report.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "sim/record/atomic_file.h"
#include "tools/report/plot.h"
#include "tools/report/report_numbers.h"

namespace metrosync {

using orbit::FamilyPoint;
using orbit::FullContinuation;
using orbit::OrbitBifurcation;

namespace {

// "KEY A_1..A_N psi_2..psi_N max|mu|" of a point
std::string plotRow(const FamilyPoint& q) {
  std::ostringstream d;
  d << reportNumber(q.p);
  for (double a : q.measures.A) d << " " << reportNumber(a);
  for (double p : q.measures.psi) d << " " << reportNumber(p);
  d << " " << reportNumber(q.orbit.maxModulus());
  return d.str();
}

// the families' rows with "stable" last (a blank line between families), then the special
// points with their type
std::string plotData(const FullContinuation& r) {
  std::ostringstream d;
  size_t specials = 0;
  for (const orbit::Family& f : r.families) {
    for (const FamilyPoint& q : f.points) d << plotRow(q) << " " << (q.stable() ? 1 : 0) << "\n";
    d << "\n";
    specials += f.special.size();
  }
  d << "\n";
  for (const orbit::Family& f : r.families)
    for (const OrbitBifurcation& s : f.special) d << plotRow(s.point) << " " << s.type << "\n";
  if (specials == 0) d << "nan" << std::string(2 * r.metronomes + 1, ' ') << "\n";
  return d.str();
}

// One panel: columns first..first+count-1 against column 1, stable solid, unstable dashed.
std::string panel(int first, int count, const std::string& name, int first_index, int stable_col,
                  int type_col) {
  std::ostringstream p;
  p << "plot ";
  for (int c = first; c < first + count; ++c) {
    const std::string label =
        name + (count > 1 || first_index > 0 ? "_" + std::to_string(c - first + first_index) : "");
    p << "data index 0 using 1:($" << stable_col << "==1?$" << c << ":1/0) with lines lc "
      << c - first + 1 << " lw 2 dt 1 title '" << label << " stable', "
      << "data index 0 using 1:($" << stable_col << "==0?$" << c << ":1/0) with lines lc "
      << c - first + 1 << " lw 1.5 dt 2 title '" << label << " unstable', "
      << "data index 1 using 1:" << c << " with points pt 7 ps 1.2 lc rgb 'black' notitle, "
      << "data index 1 using 1:" << c << ":" << type_col
      << " with labels offset 0.8,0.8 font ',9' notitle, ";
  }
  std::string s = p.str();
  return s.substr(0, s.size() - 2) + "\n";
}

}  // namespace

std::string fullDiagramScript(const FullContinuation& r, const std::string& data,
                              const std::string& png) {
  const int n = r.metronomes;
  const int mu_col = 2 + 2 * n - 1, last = mu_col + 1;  // stable (family) or type (special)
  std::ostringstream g;
  g << "set terminal pngcairo size 1000," << (n > 1 ? 1100 : 800) << " font ',11'\n"
    << "set output '" << png << "'\n"
    << "data = '" << data << "'\n"
    << "set key at screen 0.80, graph 1 left top noenhanced\nset grid\n"
    // the same margins in every panel, whatever its key's width: the panels' axes line up
    << "set lmargin at screen 0.10\nset rmargin at screen 0.78\n"
    << "set multiplot layout " << (n > 1 ? 3 : 2) << ",1 title 'periodic orbits of the full "
    << "model against " << r.param << " (section " << r.section_name << ")' noenhanced\n"
    << "set xlabel '" << r.param << "' noenhanced\nset ylabel 'A_i (orbit average)'\n"
    << panel(2, n, "A", 1, last, last);
  if (n > 1)
    g << "set ylabel 'psi_j = phi_1 - phi_j'\n" << panel(2 + n, n - 1, "psi", 2, last, last);
  // |mu| = 1, the stability border, as a curve of the panel (clipped to it, in its key)
  std::string mu_panel = panel(mu_col, 1, "max |mu|", 0, last, last);
  mu_panel.insert(mu_panel.size() - 1, ", 1 with lines dt 3 lc rgb 'gray30' title '|mu| = 1'");
  g << "set ylabel 'largest |multiplier|'\n" << mu_panel << "unset multiplot\n";
  return g.str();
}

namespace {

nlohmann::json multipliersJson(const orbit::CVec& mu) {
  nlohmann::json m = nlohmann::json::array();
  for (int i = 0; i < mu.size(); ++i)
    m.push_back({jsonNumber(mu(i).real()), jsonNumber(mu(i).imag())});
  return m;
}

}  // namespace

std::string fullBranchesCsv(const FullContinuation& r) {
  std::ostringstream c;
  c << "branch," << r.param << ",period";
  for (const std::string& s : r.section) c << ",section_" << s;
  for (int i = 1; i <= r.metronomes; ++i) c << ",A_" << i;
  for (int j = 2; j <= r.metronomes; ++j) c << ",psi_" << j;
  c << ",max_multiplier,stable";
  for (int i = 1; i <= r.metronomes; ++i) c << ",ticks_" << i;
  c << ",stick_slip,reversals,at_ticks\n";
  for (size_t b = 0; b < r.families.size(); ++b)
    for (const FamilyPoint& q : r.families[b].points) {
      c << b << "," << reportNumber(q.p) << "," << reportNumber(q.orbit.period);
      for (int k = 0; k < q.orbit.u.size(); ++k) c << "," << reportNumber(q.orbit.u(k));
      for (double a : q.measures.A) c << "," << reportNumber(a);
      for (double p : q.measures.psi) c << "," << reportNumber(p);
      c << "," << reportNumber(q.orbit.maxModulus()) << "," << (q.stable() ? 1 : 0);
      for (int t : q.measures.events.ticks) c << "," << t;
      c << "," << q.measures.events.stick_slip << "," << q.measures.events.reversals << ","
        << q.measures.events.at_ticks << "\n";
    }
  return c.str();
}

nlohmann::json fullBifurcationsJson(const FullContinuation& r) {
  nlohmann::json list = nlohmann::json::array();
  for (size_t b = 0; b < r.families.size(); ++b)
    for (const OrbitBifurcation& s : r.families[b].special)
      list.push_back({{"type", s.type},
                      {"param", r.param},
                      {"value", s.point.p},
                      {"multipliers", multipliersJson(s.point.orbit.multipliers)},
                      {"A", jsonNumbers(s.point.measures.A)},
                      {"psi", jsonNumbers(s.point.measures.psi)},
                      {"period", jsonNumber(s.point.orbit.period)},
                      {"detail", s.detail},
                      {"branch", b},
                      {"stability_changes", s.stability_changes}});
  return list;
}

nlohmann::json fullContinuationSummaryJson(const FullContinuation& r, const std::string& rig_name) {
  std::map<std::string, int> counts = {{"fold", 0},   {"torus", 0},   {"period-doubling", 0},
                                       {"branch", 0}, {"grazing", 0}, {"sliding", 0}};
  nlohmann::json branches = nlohmann::json::array();
  for (size_t b = 0; b < r.families.size(); ++b) {
    const orbit::Family& f = r.families[b];
    for (const OrbitBifurcation& s : f.special) ++counts[s.type];
    branches.push_back({{"id", b},
                        {"points", f.points.size()},
                        {"symmetry", orbit::toString(f.symmetry)},
                        {"end_backward", f.end_backward},
                        {"end_forward", f.end_forward}});
  }
  return {{"command", "continue"},
          {"model", "full"},
          {"version", metrosyncVersion()},
          {"rig", rig_name},
          {"param", r.param},
          {"from", r.from},
          {"to", r.to},
          {"start", r.start},
          {"section", r.section_name},
          {"branches", branches},
          {"bifurcations", counts},
          {"complete", true},
          {"wall_seconds", r.wall_seconds}};
}

std::vector<std::string> writeFullContinuation(const OutputDir& dir, const FullContinuation& r,
                                               const std::string& rig_name) {
  writeFileAtomically(dir.file("branches.csv"), fullBranchesCsv(r));
  writeFileAtomically(dir.file("bifurcations.json"), fullBifurcationsJson(r).dump(2) + "\n");
  std::vector<std::string> written = {"branches.csv", "bifurcations.json"};
  if (drawPng(dir, "branches.png", plotData(r), [&](const std::string& d, const std::string& p) {
        return fullDiagramScript(r, d, p);
      }))
    written.push_back("branches.png");
  writeSummary(dir, fullContinuationSummaryJson(r, rig_name));
  written.push_back("summary.json");
  return written;
}

}  // namespace metrosync
