#include "tools/report/continuation_report.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "base/number_text.h"
#include "sim/record/atomic_file.h"
#include "tools/report/plot.h"

namespace metrosync {

using continuation::CurveKind;
using continuation::FoldCurve;

namespace {

using continuation::ContinuationResult;
using continuation::ResultPoint;

// JSON has no NaN or infinity: null there.
nlohmann::json jnum(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

nlohmann::json numbers(const std::vector<double>& v) {
  nlohmann::json j = nlohmann::json::array();
  for (double x : v) j.push_back(jnum(x));
  return j;
}

// "KEY A_1..A_N psi_2..psi_N stable" rows, one block per branch; then the special points.
std::string plotData(const ContinuationResult& r) {
  std::ostringstream d;
  int branch = -1;
  for (const ResultPoint& q : r.points) {
    if (q.branch != branch && branch >= 0) d << "\n";
    branch = q.branch;
    d << numberText(q.value, 12);
    for (double a : q.A) d << " " << numberText(a, 12);
    for (double p : q.psi) d << " " << numberText(p, 12);
    d << " " << (q.stable ? 1 : 0) << "\n";
  }
  d << "\n\n";
  for (const auto& s : r.special) {
    d << numberText(s.at.value, 12);
    for (double a : s.at.A) d << " " << numberText(a, 12);
    for (double p : s.at.psi) d << " " << numberText(p, 12);
    d << " " << (s.type == "fold" ? 1 : s.type == "hopf" ? 2 : s.type == "branch" ? 3 : 4) << "\n";
  }
  if (r.special.empty()) d << "nan" << std::string(2 * r.metronomes, ' ') << "\n";
  return d.str();
}

// One panel: columns first..first+count-1 of the data against column 1.
std::string panel(int first, int count, const std::string& name, int stable_col) {
  std::ostringstream p;
  p << "plot ";
  for (int c = first; c < first + count; ++c) {
    const std::string label = name + "_" + std::to_string(c - first + (name == "A" ? 1 : 2));
    p << "data index 0 using 1:($" << stable_col << "==1?$" << c << ":1/0) with lines lc "
      << c - first + 1 << " lw 2 dt 1 title '" << label << " stable', "
      << "data index 0 using 1:($" << stable_col << "==0?$" << c << ":1/0) with lines lc "
      << c - first + 1 << " lw 1.5 dt 2 title '" << label << " unstable', "
      << "data index 1 using 1:" << c << ":($" << stable_col
      << ") with points pt 7 ps 1.2 lc rgb 'black' notitle, ";
  }
  std::string s = p.str();
  return s.substr(0, s.size() - 2) + "\n";
}

std::string diagramScript(const ContinuationResult& r, const std::string& data,
                          const std::string& png) {
  const int n = r.metronomes;
  std::ostringstream g;
  g << "set terminal pngcairo size 1000," << (n > 1 ? 900 : 500) << " font ',11'\n"
    << "set output '" << png << "'\n"
    << "data = '" << data << "'\n"
    << "set key outside right\nset grid\n"
    << "set multiplot layout " << (n > 1 ? 2 : 1) << ",1 title 'locked states of the slow flow "
    << "against " << r.param << " (points: fold, Hopf, branch, border)' noenhanced\n"
    << "set xlabel '" << r.param << "' noenhanced\nset ylabel 'A_i'\n"
    << panel(2, n, "A", 2 + 2 * n - 1);
  if (n > 1)
    g << "set ylabel 'psi_j = phi_1 - phi_j'\n" << panel(2 + n, n - 1, "psi", 2 + 2 * n - 1);
  g << "unset multiplot\n";
  return g.str();
}

std::string foldPlotScript(const ContinuationResult& r, const std::string& data,
                           const std::string& png) {
  std::ostringstream g;
  g << "set terminal pngcairo size 900,700 font ',11'\n"
    << "set output '" << png << "'\n"
    << "set grid\nset key outside right\n"
    << "set title 'fold curves (solid): locked states born or die; Hopf curves (dashed): they "
    << "start to oscillate' noenhanced\n"
    << "set xlabel '" << r.param << "' noenhanced\nset ylabel '" << r.param2 << "' noenhanced\n"
    << "plot ";
  int folds = 0, hopfs = 0;
  for (size_t i = 0; i < r.fold_curves.size(); ++i) {
    const bool fold = r.fold_curves[i].kind == CurveKind::Fold;
    g << (i ? ", " : "") << "'" << data << "' index " << i << " using 1:2 with lines lw 2 dt "
      << (fold ? 1 : 2) << " title '" << (fold ? "fold " : "Hopf ") << (fold ? folds++ : hopfs++)
      << "'";
  }
  g << "\n";
  return g.str();
}

}  // namespace

std::string foldCurveCsv(const ContinuationResult& r, CurveKind kind) {
  const bool hopf = kind == CurveKind::Hopf;
  std::ostringstream c;
  c << toString(kind) << "," << r.param << "," << r.param2;
  for (int i = 1; i <= r.metronomes; ++i) c << ",A_" << i;
  for (int j = 2; j <= r.metronomes; ++j) c << ",psi_" << j;
  c << (hopf ? ",omega\n" : "\n");
  int id = 0;
  for (const FoldCurve& curve : r.fold_curves) {
    if (curve.kind != kind) continue;
    for (const auto& q : curve.points) {
      c << id << "," << numberText(q.p1, 12) << "," << numberText(q.p2, 12);
      for (double a : q.A) c << "," << numberText(a, 12);
      for (double p : q.psi) c << "," << numberText(p, 12);
      if (hopf) c << "," << numberText(q.frequency, 12);
      c << "\n";
    }
    ++id;
  }
  return c.str();
}

std::string cyclesCsv(const ContinuationResult& r) {
  std::ostringstream c;
  c << "cycle," << r.param << ",period";
  for (int i = 1; i <= r.metronomes; ++i) c << ",A_" << i << "_min,A_" << i << "_max";
  for (int j = 2; j <= r.metronomes; ++j) c << ",psi_" << j << "_min,psi_" << j << "_max";
  c << ",stable,max_multiplier\n";
  for (const auto& cycle : r.cycles)
    for (const auto& q : cycle.points) {
      c << cycle.id << "," << numberText(q.value, 12) << "," << numberText(q.period, 12);
      for (size_t i = 0; i < q.A_min.size(); ++i)
        c << "," << numberText(q.A_min[i], 12) << "," << numberText(q.A_max[i], 12);
      for (size_t j = 0; j < q.psi_min.size(); ++j)
        c << "," << numberText(q.psi_min[j], 12) << "," << numberText(q.psi_max[j], 12);
      c << "," << (q.stable ? 1 : 0) << "," << numberText(q.max_multiplier, 12) << "\n";
    }
  return c.str();
}

std::string branchesCsv(const ContinuationResult& r) {
  std::ostringstream c;
  c << "branch," << r.param;
  for (int i = 1; i <= r.metronomes; ++i) c << ",A_" << i;
  for (int j = 2; j <= r.metronomes; ++j) c << ",psi_" << j;
  c << ",stable,max_real,ticking,platform,s\n";
  for (const ResultPoint& q : r.points) {
    c << q.branch << "," << numberText(q.value, 12);
    for (double a : q.A) c << "," << numberText(a, 12);
    for (double p : q.psi) c << "," << numberText(p, 12);
    c << "," << (q.stable ? 1 : 0) << "," << numberText(q.max_real, 12) << "," << q.ticking << ","
      << q.platform << "," << numberText(q.s, 12) << "\n";
  }
  return c.str();
}

nlohmann::json bifurcationsJson(const ContinuationResult& r) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& s : r.special) {
    nlohmann::json ev = nlohmann::json::array();
    for (const auto& e : s.at.eigenvalues) ev.push_back({jnum(e.real()), jnum(e.imag())});
    nlohmann::json j = {{"type", s.type},
                        {"param", r.param},
                        {"value", s.at.value},
                        {"A", numbers(s.at.A)},
                        {"psi", numbers(s.at.psi)},
                        {"eigenvalues", ev},
                        {"detail", s.detail},
                        {"branch", s.at.branch},
                        {"stability_changes", s.stability_changes}};
    if (s.type == "hopf") j["lyapunov"] = jnum(s.lyapunov);
    list.push_back(j);
  }
  return list;
}

nlohmann::json continuationSummaryJson(const ContinuationResult& r, const std::string& rig_name) {
  nlohmann::json branches = nlohmann::json::array();
  for (const auto& b : r.branches)
    branches.push_back({{"id", b.id},
                        {"points", b.points},
                        {"end_backward", b.end_backward},
                        {"end_forward", b.end_forward}});
  std::map<std::string, int> counts = {{"fold", 0}, {"hopf", 0}, {"branch", 0}, {"border", 0}};
  for (const auto& s : r.special) ++counts[s.type];
  nlohmann::json j = {{"command", "continue"},  {"version", metrosyncVersion()},
                      {"rig", rig_name},        {"param", r.param},
                      {"from", r.from},         {"to", r.to},
                      {"start", r.start},       {"branches", branches},
                      {"bifurcations", counts}, {"complete", true}};
  nlohmann::json cycles = nlohmann::json::array();
  for (const auto& c : r.cycles)
    cycles.push_back({{"cycle", c.id},
                      {"hopf_value", c.hopf_value},
                      {"frequency", jnum(c.frequency)},
                      {"points", c.points.size()},
                      {"end", c.end},
                      {"stability_changes", c.changes}});
  j["cycles"] = cycles;
  if (!r.param2.empty()) {
    nlohmann::json curves[2] = {nlohmann::json::array(), nlohmann::json::array()};
    for (const FoldCurve& curve : r.fold_curves) {
      nlohmann::json& list = curves[curve.kind == CurveKind::Fold ? 0 : 1];
      list.push_back({{toString(curve.kind), list.size()},
                      {"points", curve.points.size()},
                      {"end_backward", curve.end_backward},
                      {"end_forward", curve.end_forward}});
    }
    j["param2"] = r.param2;
    j["fold_curves"] = curves[0];
    j["hopf_curves"] = curves[1];
  }
  return j;
}

std::vector<std::string> writeContinuation(const OutputDir& dir, const ContinuationResult& r,
                                           const std::string& rig_name) {
  writeFileAtomically(dir.file("branches.csv"), branchesCsv(r));
  writeFileAtomically(dir.file("bifurcations.json"), bifurcationsJson(r).dump(2) + "\n");
  writeFileAtomically(dir.file("cycles.csv"), cyclesCsv(r));
  std::vector<std::string> written = {"branches.csv", "bifurcations.json", "cycles.csv"};
  if (drawPng(dir, "branches.png", plotData(r),
              [&](const std::string& d, const std::string& p) { return diagramScript(r, d, p); }))
    written.push_back("branches.png");
  if (!r.param2.empty()) {
    writeFileAtomically(dir.file("fold_curve.csv"), foldCurveCsv(r, CurveKind::Fold));
    writeFileAtomically(dir.file("hopf_curve.csv"), foldCurveCsv(r, CurveKind::Hopf));
    written.push_back("fold_curve.csv");
    written.push_back("hopf_curve.csv");
    std::ostringstream d;
    for (const auto& curve : r.fold_curves) {
      for (const auto& q : curve.points)
        d << numberText(q.p1, 12) << " " << numberText(q.p2, 12) << "\n";
      d << "\n\n";
    }
    if (!r.fold_curves.empty() && drawPng(dir, "fold_curve.png", d.str(),
                                          [&](const std::string& data, const std::string& png) {
                                            return foldPlotScript(r, data, png);
                                          }))
      written.push_back("fold_curve.png");
  }
  writeSummary(dir, continuationSummaryJson(r, rig_name));
  written.push_back("summary.json");
  return written;
}

}  // namespace metrosync
