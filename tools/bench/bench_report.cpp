#include "tools/bench/bench_report.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "base/number_text.h"
#include "tools/bench/bench_metrics.h"
#include "tools/report/plot.h"

namespace metrosync::bench {

namespace {

bool runGnuplot(const std::string& png_path, const std::string& data, const std::string& script) {
  const std::string gnuplot = findExecutable("gnuplot");
  if (gnuplot.empty()) {
    std::cerr << "metrosync_bench: warning: gnuplot not found, no " << png_path << "\n";
    return false;
  }
  const std::string tag = "." + std::to_string(::getpid()) + ".part";
  const std::string dat = png_path + ".dat" + tag, gp = png_path + ".gp" + tag,
                    png = png_path + tag;
  {
    std::ofstream(dat) << data;
    std::string s = script;
    for (auto [key, val] : {std::pair<std::string, std::string>{"@DATA@", gnuplotQuote(dat)},
                            {"@PNG@", gnuplotQuote(png)}}) {
      for (size_t p; (p = s.find(key)) != std::string::npos;) s.replace(p, key.size(), val);
    }
    std::ofstream(gp) << s;
  }
  const int rc = std::system(("'" + gnuplot + "' '" + gp + "' 2>/dev/null").c_str());
  bool ok = rc == 0 && std::filesystem::exists(png);
  if (ok) std::filesystem::rename(png, png_path);
  std::filesystem::remove(dat);
  std::filesystem::remove(gp);
  std::filesystem::remove(png);
  if (!ok) std::cerr << "metrosync_bench: warning: gnuplot failed, no " << png_path << "\n";
  return ok;
}

std::vector<std::string> labelsInOrder(const std::vector<Record>& records) {
  std::vector<std::string> labels;
  for (const Record& r : records)
    if (std::find(labels.begin(), labels.end(), r.method.label()) == labels.end())
      labels.push_back(r.method.label());
  return labels;
}

}  // namespace

std::string csvHeader() {
  return "scene,n,periods,engine,integrator,setting,accuracy,steps_per_period,status,note,runs,"
         "wall_median_s,wall_min_s,wall_max_s,cpu_median_s,load1_min,load1_max,err_envelope,"
         "max_abs_dA,max_abs_dpsi,err_final_state,rows_compared,steps,rhs_evals,events,ticks,"
         "stick_slip,regime,wall_final_median_s,cpu_final_median_s,final_sampled_diff,"
         "engine_median_s,wall_over_engine";
}

std::string csvRow(const Record& r) {
  std::ostringstream os;
  os << csvField(r.scene) << ',' << r.n_metronomes << ',' << benchNumber(r.periods, 6) << ','
     << r.method.engine << ',' << r.method.integrator << ',' << r.method.setting() << ','
     << benchNumber(r.method.accuracy > 0 ? r.method.accuracy : NAN, 6) << ','
     << benchNumber(r.method.steps_per_period > 0 ? r.method.steps_per_period : NAN, 6) << ','
     << csvField(r.status) << ',' << csvField(r.note) << ',' << r.runs << ','
     << benchNumber(r.wall_median_s, 6) << ',' << benchNumber(r.wall_min_s, 6) << ','
     << benchNumber(r.wall_max_s, 6) << ',' << benchNumber(r.cpu_median_s, 6) << ','
     << benchNumber(r.load_min, 2, Notation::Fixed) << ','
     << benchNumber(r.load_max, 2, Notation::Fixed) << ',' << benchNumber(r.error.envelope, 6)
     << ',' << benchNumber(r.error.max_dA, 6) << ',' << benchNumber(r.error.max_dpsi, 6) << ','
     << benchNumber(r.error.final_state, 6) << ',' << r.error.rows << ',' << r.steps << ','
     << r.rhs_evals << ',' << r.events << ',' << r.ticks << ',' << r.stick_slip << ','
     << csvField(r.regime) << ',' << benchNumber(r.wall_final_median_s, 6) << ','
     << benchNumber(r.cpu_final_median_s, 6) << ',' << benchNumber(r.final_sampled_diff, 6) << ','
     << benchNumber(r.engine_median_s, 6) << ',' << benchNumber(r.wall_over_engine, 6);
  return os.str();
}

std::string recordsCsv(const std::vector<Record>& records) {
  std::string s = csvHeader() + "\n";
  for (const Record& r : records) s += csvRow(r) + "\n";
  return s;
}

std::string precisionTable(const std::vector<Record>& records) {
  std::ostringstream os;
  os << "| engine:integrator | setting | final-state error | CPU s, no samples | wall s, no "
        "samples | envelope error | max abs dA | max abs dpsi | CPU s, envelope | wall s, "
        "envelope (runs) | steps | rhs evals | events | ticks | stick-slip | regime | status |\n";
  os << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto err = [&](const Record& r, double v) {
    const bool has = r.status == "ok" || r.status == "cross-check";
    return r.status == "reference" ? std::string("-")
           : has                   ? benchNumber(v, 1, Notation::Scientific)
                                   : std::string();
  };
  auto line = [&](const Record& r) {
    const bool ran = r.status != "skipped (predicted over budget)";
    // the programs (the careful peer, `metrosync run`): one timing, their own medians
    const bool peer = r.method.engine == "peer" || r.method.engine == "run";
    os << "| " << r.method.label() << " | " << r.method.setting() << " | "
       << err(r, r.error.final_state) << " | "
       << (r.timed() ? benchNumber(peer ? r.cpu_median_s : r.cpu_final_median_s, 3) : "") << " | "
       << (r.timed() ? benchNumber(peer ? r.wall_median_s : r.wall_final_median_s, 3) : "") << " | "
       << err(r, r.error.envelope) << " | " << err(r, r.error.max_dA) << " | "
       << err(r, r.error.max_dpsi) << " | "
       << (r.timed() && !peer ? benchNumber(r.cpu_median_s, 3) : "") << " | ";
    if (r.timed() && !peer)
      os << benchNumber(r.wall_median_s, 3) << " (" << r.runs << ")";
    else if (r.timed())
      os << "(" << r.runs << (r.method.engine == "run" ? " runs of the command)" : " in the peer)");
    else if (r.status == "over budget")
      os << "> " << benchNumber(r.wall_median_s, 0, Notation::Fixed);
    os << " | ";
    if (ran && r.status != "over budget" && r.steps > 0)
      os << r.steps << " | " << r.rhs_evals << " | " << r.events << " | " << r.ticks << " | "
         << r.stick_slip << " | " << r.regime << " | ";
    else
      os << " |  |  |  |  |  | ";
    os << r.status << (r.note.empty() ? "" : ": " + r.note) << " |\n";
  };
  for (const Record& r : records)
    if (r.status == "reference" || r.status == "cross-check") line(r);
  for (const Record& r : records)
    if (r.status != "reference" && r.status != "cross-check") line(r);
  return os.str();
}

double finalStateCpu(const Record& r) {
  return r.method.engine == "peer" || r.method.engine == "run" ||
                 !std::isfinite(r.cpu_final_median_s)
             ? r.cpu_median_s
             : r.cpu_final_median_s;
}

std::vector<WorkPoint> frontOf(const std::vector<Record>& records, const std::string& who,
                               bool final_state) {
  std::vector<WorkPoint> pts;
  for (const Record& r : records) {
    if (r.status != "ok" || !r.timed()) continue;
    if (r.method.engine != who && r.method.label() != who) continue;
    if (final_state)
      pts.push_back({r.error.final_state, finalStateCpu(r)});
    else
      pts.push_back({r.error.envelope, r.cpu_median_s});
  }
  return paretoFront(pts);
}

std::string ratiosMarkdown(const std::vector<Record>& records, std::string& csv_rows) {
  const std::string scene = records.empty() ? "" : records.front().scene;
  std::ostringstream os;
  for (const bool final_state : {true, false}) {
    const std::string measure = final_state ? "final-state" : "envelope";
    std::vector<std::string> engines;
    for (const char* e : {"direct", "peer", "odeint", "simbody", "siconos"})
      if (!frontOf(records, e, final_state).empty()) engines.push_back(e);
    for (size_t i = 0; i < engines.size(); ++i) {
      for (size_t j = i + 1; j < engines.size(); ++j) {
        const auto a = frontOf(records, engines[i], final_state);
        const auto b = frontOf(records, engines[j], final_state);
        const auto rs = ratiosAtEqualError(a, b);
        os << "- **" << engines[i] << " / " << engines[j] << "**, " << measure
           << " error (best integrator of each at each error): ";
        if (rs.empty()) {
          // no common error: say where each front lies
          os << "no common error range (" << engines[i] << " reaches "
             << benchNumber(a.front().error, 1, Notation::Scientific) << " ... "
             << benchNumber(a.back().error, 1, Notation::Scientific) << " in "
             << benchNumber(a.front().time_s, 3) << " ... " << benchNumber(a.back().time_s, 3)
             << " s; " << engines[j] << " " << benchNumber(b.front().error, 1, Notation::Scientific)
             << " ... " << benchNumber(b.back().error, 1, Notation::Scientific) << " in "
             << benchNumber(b.front().time_s, 3) << " ... " << benchNumber(b.back().time_s, 3)
             << " s)\n";
          continue;
        }
        os << "geometric mean " << benchNumber(geometricMeanRatio(rs), 3) << " over errors "
           << benchNumber(rs.front().error, 1, Notation::Scientific) << " ... "
           << benchNumber(rs.back().error, 1, Notation::Scientific) << "; ";
        for (size_t k = 0; k < rs.size(); ++k) {
          os << (k ? ", " : "") << benchNumber(rs[k].ratio(), 3) << " at "
             << benchNumber(rs[k].error, 1, Notation::Scientific) << " ("
             << benchNumber(rs[k].time_a_s, 3) << " s / " << benchNumber(rs[k].time_b_s, 3)
             << " s)";
          csv_rows += measure + "," + csvField(scene) + "," + engines[i] + "," + engines[j] + "," +
                      benchNumber(rs[k].error, 6) + "," + benchNumber(rs[k].time_a_s, 6) + "," +
                      benchNumber(rs[k].time_b_s, 6) + "," + benchNumber(rs[k].ratio(), 6) + "\n";
        }
        os << "\n";
      }
    }
  }
  return os.str();
}

namespace {

// One gnuplot data block per engine:integrator of (error, CPU time) points; their titles.
std::string workPrecisionBlocks(const std::vector<Record>& records, bool final_state,
                                std::vector<std::string>& titles) {
  std::ostringstream data;
  for (const std::string& label : labelsInOrder(records)) {
    std::ostringstream block;
    int n = 0;
    for (const Record& r : records) {
      if (r.method.label() != label || r.status != "ok" || !r.timed()) continue;
      const double e = final_state ? r.error.final_state : r.error.envelope;
      const double t = final_state ? finalStateCpu(r) : r.cpu_median_s;
      if (!(e > 0) || !(t > 0)) continue;
      block << e << ' ' << t << ' ' << gnuplotQuote(r.method.setting()) << '\n';
      ++n;
    }
    if (n == 0) continue;
    data << "# " << label << "\n" << block.str() << "\n\n";
    titles.push_back(label);
  }
  return data.str();
}

// Point type and dash by engine; the colour by the label's place among all labels, so that a
// method has the same colour in both panels.
std::string curveStyle(const std::string& label, const std::vector<std::string>& all) {
  static const char* const kColours[] = {"#9400d3", "#009e73", "#56b4e9", "#e69f00",
                                         "#d55e00", "#0072b2", "#cc79a7", "#000000"};
  const size_t k = std::find(all.begin(), all.end(), label) - all.begin();
  const bool siconos = label.rfind("siconos", 0) == 0;
  const bool direct = label.rfind("direct", 0) == 0;
  const bool peer = label.rfind("peer", 0) == 0;
  return std::string(" pt ") +
         (siconos  ? "9"
          : direct ? "7"
          : peer   ? "13"
                   : "5") +
         " dt " +
         (siconos  ? "2"
          : direct ? "1"
          : peer   ? "3"
                   : "4") +
         " lc rgb '" + kColours[k % (sizeof kColours / sizeof kColours[0])] + "'";
}

// One panel: the blocks from `first` on.
std::string workPrecisionPanel(const std::vector<std::string>& titles, size_t first,
                               const std::vector<std::string>& all, const std::string& xlabel,
                               const std::string& ylabel) {
  std::ostringstream gp;
  gp << "set xlabel " << gnuplotQuote(xlabel) << "\nset ylabel " << gnuplotQuote(ylabel)
     << "\nplot ";
  for (size_t k = 0; k < titles.size(); ++k)
    gp << (k ? ", " : "") << "@DATA@ index " << first + k << " using 1:2 with linespoints lw 2"
       << curveStyle(titles[k], all) << " title " << gnuplotQuote(titles[k]);
  gp << "\n";
  return gp.str();
}

}  // namespace

bool plotWorkPrecision(const std::string& png_path, const std::vector<Record>& records,
                       const std::string& title) {
  std::vector<std::string> final_titles, env_titles;
  const std::string data = workPrecisionBlocks(records, true, final_titles) +
                           workPrecisionBlocks(records, false, env_titles);
  if (final_titles.empty() && env_titles.empty()) return false;
  const std::vector<std::string> all = labelsInOrder(records);
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1600,700 font 'Sans,11'\nset output @PNG@\n"
     << "set multiplot layout 1," << (env_titles.empty() || final_titles.empty() ? 1 : 2)
     << " title " << gnuplotQuote(title) << "\nset logscale xy\nset format x '10^{%L}'\n"
     << "set format y '10^{%L}'\nset grid\nset key left top\nset xrange [*:*] reverse\n";
  if (!final_titles.empty())
    gp << workPrecisionPanel(final_titles, 0, all,
                             "final-state error: max |d(xdot, theta_i, thetadot_i)| against the "
                             "reference (scaled)",
                             "CPU time, median of the runs without samples (s)");
  if (!env_titles.empty())
    gp << workPrecisionPanel(env_titles, final_titles.size(), all,
                             "envelope error: max(max |dA_i|, max |dpsi_j|) against the "
                             "reference (scaled)",
                             "CPU time, median of the runs recording the envelope (s)");
  gp << "unset multiplot\n";
  return runGnuplot(png_path, data, gp.str());
}

bool plotNScaling(const std::string& png_path, const std::vector<Record>& records,
                  const std::string& title) {
  // two panels: the cost per fast period against N (with guides proportional to N and to N^2
  // through the first curve's first point), and the cost per step and metronome against N
  std::ostringstream data;
  std::vector<std::string> titles;
  for (const std::string& label : labelsInOrder(records)) {
    std::ostringstream block;
    int n = 0;
    std::string setting;
    for (const Record& r : records) {
      if (r.method.label() != label || !r.timed() || r.steps <= 0) continue;
      block << r.n_metronomes << ' ' << r.wall_median_s / r.periods << ' '
            << 1e6 * r.wall_median_s / (static_cast<double>(r.steps) * r.n_metronomes) << '\n';
      setting = r.method.setting();
      ++n;
    }
    if (n == 0) continue;
    data << "# " << label << "\n" << block.str() << "\n\n";
    titles.push_back(label + " " + setting);
  }
  if (titles.empty()) return false;
  int n_max = 0;
  for (const Record& q : records) n_max = std::max(n_max, q.n_metronomes);
  for (const Record& r : records) {
    if (!r.timed() || r.steps <= 0) continue;
    const double c0 = r.wall_median_s / r.periods, n0 = r.n_metronomes;
    data << "# proportional to N\n"
         << n0 << ' ' << c0 << "\n"
         << n_max << ' ' << c0 * n_max / n0 << "\n\n\n"
         << "# proportional to N^2\n"
         << n0 << ' ' << c0 << "\n"
         << n_max << ' ' << c0 * (n_max / n0) * (n_max / n0) << "\n\n\n";
    break;
  }
  const size_t k_lin = titles.size(), k_sq = titles.size() + 1;
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1400,600 font 'Sans,11'\nset output @PNG@\n"
     << "set multiplot layout 1,2 title " << gnuplotQuote(title) << "\nset logscale xy\nset grid\n"
     << "set xlabel 'N (metronomes)'\nset key left top\n"
     << "set format y '10^{%L}'\nset ylabel 'wall time per fast period, median (s)'\nplot ";
  for (size_t k = 0; k < titles.size(); ++k)
    gp << (k ? ", " : "") << "@DATA@ index " << k << " using 1:2 with linespoints lw 2 title "
       << gnuplotQuote(titles[k]);
  gp << ", @DATA@ index " << k_lin << " using 1:2 with lines dt 2 lw 1.5 lc 'gray40' title "
     << "'proportional to N', @DATA@ index " << k_sq
     << " using 1:2 with lines dt 3 lw 1.5 lc 'gray20' title 'proportional to N^2'\n"
     << "set format y '%g'\nset ylabel 'wall time per step and metronome, median (us)'\nplot ";
  for (size_t k = 0; k < titles.size(); ++k)
    gp << (k ? ", " : "") << "@DATA@ index " << k << " using 1:3 with linespoints lw 2 title "
       << gnuplotQuote(titles[k]);
  gp << "\nunset multiplot\n";
  return runGnuplot(png_path, data.str(), gp.str());
}

std::string nscaleTable(const std::vector<Record>& records) {
  std::ostringstream os;
  const auto labels = labelsInOrder(records);
  std::set<int> ns;
  for (const Record& r : records) ns.insert(r.n_metronomes);
  os << "| N |";
  for (const auto& l : labels) os << " " << l << " ms/period | steps/period | us/(step N) |";
  os << "\n|---|";
  for (size_t k = 0; k < labels.size(); ++k) os << "---|---|---|";
  os << "\n";
  for (int n : ns) {
    os << "| " << n << " |";
    for (const auto& l : labels) {
      std::string cell = " |  |  |";
      for (const Record& r : records)
        if (r.n_metronomes == n && r.method.label() == l) {
          if (r.timed() && r.steps > 0)
            cell = benchNumber(1e3 * r.wall_median_s / r.periods, 3) + " | " +
                   benchNumber(static_cast<double>(r.steps) / r.periods, 3) + " | " +
                   benchNumber(1e6 * r.wall_median_s / (static_cast<double>(r.steps) * n), 3) +
                   " |";
          else
            cell = r.status + " |  |  |";
        }
      os << " " << cell;
    }
    os << "\n";
  }
  return os.str();
}

}  // namespace metrosync::bench
