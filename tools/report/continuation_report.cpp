#include "tools/report/continuation_report.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "base/number_text.h"
#include "sim/record/atomic_file.h"
#include "tools/report/continuation_diagram.h"
#include "tools/report/json_file.h"
#include "tools/report/plot.h"
#include "tools/report/report_numbers.h"

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
  c << ",stable,max_multiplier";
  for (int i = 1; i <= r.metronomes; ++i) c << ",A_" << i << "_0";
  for (int j = 2; j <= r.metronomes; ++j) c << ",psi_" << j << "_0";
  c << "\n";
  for (const auto& cycle : r.cycles)
    for (const auto& q : cycle.points) {
      c << cycle.id << "," << numberText(q.value, 12) << "," << numberText(q.period, 12);
      for (size_t i = 0; i < q.A_min.size(); ++i)
        c << "," << numberText(q.A_min[i], 12) << "," << numberText(q.A_max[i], 12);
      for (size_t j = 0; j < q.psi_min.size(); ++j)
        c << "," << numberText(q.psi_min[j], 12) << "," << numberText(q.psi_max[j], 12);
      c << "," << (q.stable ? 1 : 0) << "," << numberText(q.max_multiplier, 12);
      for (double a : q.A0) c << "," << numberText(a, 12);
      for (double p : q.psi0) c << "," << numberText(p, 12);
      c << "\n";
    }
  return c.str();
}

std::string branchesCsv(const ContinuationResult& r) {
  std::ostringstream c;
  c << "branch," << r.param;
  for (int i = 1; i <= r.metronomes; ++i) c << ",A_" << i;
  for (int j = 2; j <= r.metronomes; ++j) c << ",psi_" << j;
  c << ",stable,max_real,ticking,platform,s,weight\n";
  for (const ResultPoint& q : r.points) {
    c << q.branch << "," << numberText(q.value, 12);
    for (double a : q.A) c << "," << numberText(a, 12);
    for (double p : q.psi) c << "," << numberText(p, 12);
    // max_real, s and weight may have no value (a border state, mu = 0, an inner state)
    c << "," << (q.stable ? 1 : 0) << "," << optionalCell(q.max_real) << "," << q.ticking << ","
      << q.platform << "," << optionalCell(q.s) << "," << optionalCell(q.weight) << "\n";
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

namespace {

nlohmann::json branchesJson(const ContinuationResult& r) {
  nlohmann::json branches = nlohmann::json::array();
  for (const auto& b : r.branches) {
    nlohmann::json j = {{"id", b.id},
                        {"points", b.points},
                        {"end_backward", b.end_backward},
                        {"end_forward", b.end_forward},
                        {"max_points", b.max_points}};
    if (b.neutral) j["family"] = b.neutral;
    branches.push_back(j);
  }
  return branches;
}

nlohmann::json familiesJson(const ContinuationResult& r) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& f : r.families)
    list.push_back({{"family", f.id},
                    {"branch", f.branch},
                    {"neutral", f.neutral},
                    {"cause", f.cause},
                    {"points", f.points.size()},
                    {"ends", f.points.empty() ? "" : f.points.front().ends}});
  return list;
}

nlohmann::json cyclesJson(const ContinuationResult& r) {
  nlohmann::json cycles = nlohmann::json::array();
  for (const auto& c : r.cycles) {
    nlohmann::json folds = nlohmann::json::array();
    for (const auto& f : c.folds)
      folds.push_back({{"value", f.at.value},
                       {"period", f.at.period},
                       {"confirmed", f.confirmed},
                       {"check", f.check}});
    cycles.push_back({{"cycle", c.id},
                      {"hopf_value", c.hopf_value},
                      {"frequency", jnum(c.frequency)},
                      {"points", c.points.size()},
                      {"budget", r.cycle_budget},
                      {"max_points", c.max_points},
                      {"end", c.end},
                      {"folds", folds},
                      {"stability_changes", c.changes}});
  }
  return cycles;
}

nlohmann::json curvesJson(const ContinuationResult& r, CurveKind kind) {
  nlohmann::json list = nlohmann::json::array();
  for (const FoldCurve& curve : r.fold_curves) {
    if (curve.kind != kind) continue;
    nlohmann::json j = {{toString(kind), list.size()},
                        {"points", curve.points.size()},
                        {"end_backward", curve.end_backward},
                        {"end_forward", curve.end_forward}};
    if (!curve.failure.empty()) j["failure"] = curve.failure;
    list.push_back(j);
  }
  return list;
}

}  // namespace

nlohmann::json continuationSummaryJson(const ContinuationResult& r, const std::string& rig_name) {
  std::map<std::string, int> counts = {{"fold", 0}, {"hopf", 0}, {"branch", 0}, {"border", 0}};
  for (const auto& s : r.special) ++counts[s.type];
  nlohmann::json j = {{"command", "continue"},  {"version", metrosyncVersion()},
                      {"rig", rig_name},        {"param", r.param},
                      {"from", r.from},         {"to", r.to},
                      {"start", r.start},       {"branches", branchesJson(r)},
                      {"bifurcations", counts}, {"complete", true}};
  j["families"] = familiesJson(r);
  j["cycles"] = cyclesJson(r);
  if (!r.param2.empty()) {
    j["param2"] = r.param2;
    j["fold_curves"] = curvesJson(r, CurveKind::Fold);
    j["hopf_curves"] = curvesJson(r, CurveKind::Hopf);
  }
  return j;
}

std::string familiesCsv(const ContinuationResult& r) {
  std::ostringstream c;
  c << "family," << r.param;
  for (int i = 1; i <= r.metronomes; ++i) c << ",A_" << i << "_min,A_" << i << "_max";
  for (int j = 2; j <= r.metronomes; ++j) c << ",psi_" << j << "_min,psi_" << j << "_max";
  c << ",closed\n";
  for (const auto& f : r.families)
    for (const auto& q : f.points) {
      c << f.id << "," << numberText(q.value, 12);
      for (size_t i = 0; i < q.A_min.size(); ++i)
        c << "," << numberText(q.A_min[i], 12) << "," << numberText(q.A_max[i], 12);
      for (size_t j = 0; j < q.psi_min.size(); ++j)
        c << "," << numberText(q.psi_min[j], 12) << "," << numberText(q.psi_max[j], 12);
      c << "," << (q.closed ? 1 : 0) << "\n";
    }
  return c.str();
}

std::vector<std::string> writeContinuation(const OutputDir& dir, const ContinuationResult& r,
                                           const std::string& rig_name) {
  writeFileAtomically(dir.file("branches.csv"), branchesCsv(r));
  writeJsonFile(dir.file("bifurcations.json"), bifurcationsJson(r));
  writeFileAtomically(dir.file("cycles.csv"), cyclesCsv(r));
  writeFileAtomically(dir.file("families.csv"), familiesCsv(r));
  std::vector<std::string> written = {"branches.csv", "bifurcations.json", "cycles.csv",
                                      "families.csv"};
  if (drawPng(dir, "branches.png", continuationDiagramData(r),
              [&](const std::string& d, const std::string& p) {
                return continuationDiagramScript(r, d, p);
              }))
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
