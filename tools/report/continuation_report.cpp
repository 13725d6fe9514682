#include "tools/report/continuation_report.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "sim/record/atomic_file.h"
#include "tools/report/plot.h"

namespace metrosync {

namespace {

using continuation::ContinuationResult;
using continuation::ResultPoint;

std::string num(double v) {
  if (std::isnan(v)) return "nan";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return buf;
}

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
    d << num(q.value);
    for (double a : q.A) d << " " << num(a);
    for (double p : q.psi) d << " " << num(p);
    d << " " << (q.stable ? 1 : 0) << "\n";
  }
  d << "\n\n";
  for (const auto& s : r.special) {
    d << num(s.at.value);
    for (double a : s.at.A) d << " " << num(a);
    for (double p : s.at.psi) d << " " << num(p);
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
    << "set title 'fold curves: where locked states are born or die' noenhanced\n"
    << "set xlabel '" << r.param << "' noenhanced\nset ylabel '" << r.param2 << "' noenhanced\n"
    << "plot for [i=0:" << r.fold_curves.size() - 1 << "] '" << data
    << "' index i using 1:2 with lines lw 2 title sprintf('fold %d', i)\n";
  return g.str();
}

}  // namespace

std::string foldCurveCsv(const ContinuationResult& r) {
  std::ostringstream c;
  c << "fold," << r.param << "," << r.param2;
  for (int i = 1; i <= r.metronomes; ++i) c << ",A_" << i;
  for (int j = 2; j <= r.metronomes; ++j) c << ",psi_" << j;
  c << "\n";
  for (size_t f = 0; f < r.fold_curves.size(); ++f)
    for (const auto& q : r.fold_curves[f].points) {
      c << f << "," << num(q.p1) << "," << num(q.p2);
      for (double a : q.A) c << "," << num(a);
      for (double p : q.psi) c << "," << num(p);
      c << "\n";
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
    c << q.branch << "," << num(q.value);
    for (double a : q.A) c << "," << num(a);
    for (double p : q.psi) c << "," << num(p);
    c << "," << (q.stable ? 1 : 0) << "," << num(q.max_real) << "," << q.ticking << ","
      << q.platform << "," << num(q.s) << "\n";
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
  if (!r.param2.empty()) {
    nlohmann::json curves = nlohmann::json::array();
    for (size_t f = 0; f < r.fold_curves.size(); ++f)
      curves.push_back({{"fold", f},
                        {"points", r.fold_curves[f].points.size()},
                        {"end_backward", r.fold_curves[f].end_backward},
                        {"end_forward", r.fold_curves[f].end_forward}});
    j["param2"] = r.param2;
    j["fold_curves"] = curves;
  }
  return j;
}

std::vector<std::string> writeContinuation(const OutputDir& dir, const ContinuationResult& r,
                                           const std::string& rig_name) {
  writeFileAtomically(dir.file("branches.csv"), branchesCsv(r));
  writeFileAtomically(dir.file("bifurcations.json"), bifurcationsJson(r).dump(2) + "\n");
  std::vector<std::string> written = {"branches.csv", "bifurcations.json"};
  if (drawPng(dir, "branches.png", plotData(r),
              [&](const std::string& d, const std::string& p) { return diagramScript(r, d, p); }))
    written.push_back("branches.png");
  if (!r.param2.empty()) {
    writeFileAtomically(dir.file("fold_curve.csv"), foldCurveCsv(r));
    written.push_back("fold_curve.csv");
    std::ostringstream d;
    for (const auto& curve : r.fold_curves) {
      for (const auto& q : curve.points) d << num(q.p1) << " " << num(q.p2) << "\n";
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
