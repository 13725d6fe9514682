#include "tools/bench/process_phases.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "tools/bench/bench_metrics.h"

namespace metrosync::bench {

namespace {

constexpr const char* kPrefix = "metrosync: phase ";

// What each part of the process is (docs for the table).
std::string partMeaning(const std::string& name) {
  if (name == "start-up") return "exec to main: the loader, shared libraries, static set-up";
  if (name == "args") return "main to the command: its options parsed";
  if (name == "rig") return "the rig read, parsed and checked, its engine chosen";
  if (name == "folder") return "the output folder made, stale files removed, the files opened";
  if (name == "run") return "the engine's run (wall_seconds, and the engine's own set-up)";
  if (name == "files") return "the rows left to write when the run ended, the files closed";
  if (name == "sync") return "fsync, the renames, the folder's sync";
  if (name == "plot") return "the envelope plot (gnuplot)";
  if (name == "summary") return "the regime's verdict, summary.json made and written";
  if (name == "print") return "what run prints (nothing with --quiet)";
  if (name == "exit") return "after the last phase: destructors, exit, the parent's wait";
  return "";
}

double sum(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s;
}

}  // namespace

double processBudget(double wall_seconds) {
  return 1.5 * wall_seconds + 3e-3;
}

PhaseMarks parsePhases(const std::string& text) {
  PhaseMarks m;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(kPrefix, 0) != 0) continue;
    char name[64] = {};
    double ms = 0, at = 0;
    const char* rest = line.c_str() + std::char_traits<char>::length(kPrefix);
    if (m.names.empty() && std::isnan(m.main_at)) {
      if (std::sscanf(rest, "main at %lf s", &at) != 1)
        throw std::invalid_argument("the first phase line is not 'main at T s': " + line);
      m.main_at = m.last_at = at;
      continue;
    }
    if (std::sscanf(rest, "%63s %lf ms (at %lf s)", name, &ms, &at) != 3 || !(ms >= 0))
      throw std::invalid_argument("a phase line that is not 'NAME MS ms (at T s)': " + line);
    m.names.push_back(name);
    m.ms.push_back(ms);
    m.last_at = at;
  }
  if (std::isnan(m.main_at)) throw std::invalid_argument("no phase line (METROSYNC_PHASES=1?)");
  return m;
}

ProcessBreakdown processBreakdown(const std::vector<ProcessSample>& runs) {
  if (runs.empty()) throw std::invalid_argument("no run to break down");
  ProcessBreakdown b;
  b.runs = static_cast<int>(runs.size());
  b.phases = {"start-up"};
  for (const std::string& n : runs.front().marks.names) b.phases.push_back(n);
  b.phases.push_back("exit");
  std::vector<std::vector<double>> parts(b.phases.size());
  std::vector<double> total, cpu, wall, unaccounted;
  for (const ProcessSample& r : runs) {
    if (r.marks.names != runs.front().marks.names)
      throw std::invalid_argument("the runs' phases differ");
    std::vector<double> p = {1e3 * (r.marks.main_at - r.start_s)};
    for (double ms : r.marks.ms) p.push_back(ms);
    p.push_back(1e3 * (r.end_s - r.marks.last_at));
    for (size_t k = 0; k < p.size(); ++k) parts[k].push_back(p[k]);
    total.push_back(1e3 * (r.end_s - r.start_s));
    unaccounted.push_back(total.back() - sum(p));
    cpu.push_back(1e3 * r.cpu_s);
    wall.push_back(1e3 * r.wall_seconds);
  }
  for (const auto& v : parts) b.ms.push_back(median(v));
  b.total_ms = median(total);
  b.cpu_ms = median(cpu);
  b.wall_seconds_ms = median(wall);
  b.budget_ms = 1e3 * processBudget(1e-3 * b.wall_seconds_ms);
  b.unaccounted_ms = median(unaccounted);
  return b;
}

std::string processMarkdown(const ProcessBreakdown& b, const std::string& command) {
  std::ostringstream os;
  os << "**The whole process: " << benchNumber(b.total_ms, 3) << " ms against its budget "
     << benchNumber(b.budget_ms, 3) << " ms (1.5 x wall_seconds "
     << benchNumber(b.wall_seconds_ms, 3) << " ms + 3 ms): " << (b.met() ? "met" : "NOT met")
     << "**"
     << (b.met() ? ""
                 : " (over by " + benchNumber(b.total_ms - b.budget_ms, 3) + " ms, " +
                       benchNumber(b.total_ms / b.budget_ms, 2, Notation::Fixed) + "x)")
     << ". Medians of " << b.runs << " runs; process CPU " << benchNumber(b.cpu_ms, 3)
     << " ms.\n\nWhere each millisecond goes (the median of each part; METROSYNC_PHASES=1 for "
        "the parts inside the program, the start-up and the exit from outside on the same "
        "clock; each run's parts tile it to "
     << benchNumber(std::abs(b.unaccounted_ms) < 5e-3 ? 0.0 : b.unaccounted_ms, 2, Notation::Fixed)
     << " ms, while the medians of the parts need not add up to the median of the whole):\n\n"
     << "| part | ms | share | what it is |\n|---|---|---|---|\n";
  for (size_t k = 0; k < b.phases.size(); ++k)
    os << "| " << b.phases[k] << " | " << benchNumber(b.ms[k], 3) << " | "
       << benchNumber(100 * b.ms[k] / b.total_ms, 2) << "% | " << partMeaning(b.phases[k])
       << " |\n";
  os << "| whole process | " << benchNumber(b.total_ms, 3) << " | 100% | from outside |\n";
  if (!command.empty()) os << "\nMade by:\n\n    " << command << "\n";
  return os.str();
}

std::string processCsv(const ProcessBreakdown& b, const std::string& scene, double load_min,
                       double load_max) {
  std::string s =
      "scene,runs,total_ms,wall_seconds_ms,budget_ms,cpu_ms,unaccounted_ms,load1_min,load1_max";
  for (const std::string& p : b.phases) s += "," + p + "_ms";
  s += "\n" + csvField(scene) + "," + std::to_string(b.runs) + "," + benchNumber(b.total_ms, 6) +
       "," + benchNumber(b.wall_seconds_ms, 6) + "," + benchNumber(b.budget_ms, 6) + "," +
       benchNumber(b.cpu_ms, 6) + "," + benchNumber(b.unaccounted_ms, 6) + "," +
       benchNumber(load_min, 2, Notation::Fixed) + "," + benchNumber(load_max, 2, Notation::Fixed);
  for (double ms : b.ms) s += "," + benchNumber(ms, 6);
  return s + "\n";
}

}  // namespace metrosync::bench
