#include "tools/bench/continue_cost.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "tools/bench/bench_metrics.h"
#include "tools/bench/subprocess.h"

namespace metrosync::bench {

namespace {

namespace fs = std::filesystem;

long csvRows(const fs::path& p) {
  std::ifstream in(p);
  long n = -1;  // the header
  for (std::string line; std::getline(in, line);) n += line.empty() ? 0 : 1;
  return std::max(0L, n);
}

ContinueCostRow measureOne(const ContinueCostOptions& o, const BenchOptions& c,
                           const std::string& rig, const fs::path& out) {
  ContinueCostRow row;
  row.rig = rig;
  std::vector<std::string> argv = {o.metrosync, "continue", rig};
  argv.insert(argv.end(), o.args.begin(), o.args.end());
  argv.push_back("-q");
  row.command = shellCommand(argv);
  argv.insert(argv.end(), {"--out", out.string()});
  std::vector<double> walls, cpus, loads;
  for (int k = 0; k < o.repeat; ++k) {
    loads.push_back(waitForLoad(c));
    const ProcessResult pr = runProcess(argv, o.timeout_s);
    walls.push_back(pr.wall_s), cpus.push_back(pr.cpu_s);
    row.points = csvRows(out / "branches.csv");
    fs::remove_all(out);
    if (!pr.ok()) {
      row.timed_out = pr.timed_out;
      row.failure = pr.timed_out ? "stopped after " + benchNumber(o.timeout_s, 3) + " s"
                                 : "exit " + std::to_string(pr.exit_code) + ": " +
                                       (pr.err.empty() ? pr.error : pr.err.substr(0, 200));
      break;
    }
  }
  row.runs = static_cast<int>(walls.size());
  row.wall_s = median(walls), row.cpu_s = median(cpus);
  row.load_min = *std::min_element(loads.begin(), loads.end());
  row.load_max = std::max(*std::max_element(loads.begin(), loads.end()), loadAverage1());
  return row;
}

std::string verdictOf(const ContinueCostRow& r) {
  if (r.timed_out) return "NOT met (not finished in " + benchNumber(r.wall_s, 3) + " s)";
  if (!r.failure.empty()) return "failed: " + r.failure;
  if (r.wall_s <= kContinueTargetS) return "met";
  return "NOT met (" + benchNumber(r.wall_s / kContinueTargetS, 3) + "x the target)";
}

}  // namespace

std::vector<ContinueCostRow> measureContinueCost(const ContinueCostOptions& o,
                                                 const BenchOptions& c) {
  const fs::path out =
      fs::temp_directory_path() / ("metrosync-bench-continue-" + std::to_string(::getpid()));
  std::vector<ContinueCostRow> rows;
  for (const std::string& rig : o.rigs) {
    rows.push_back(measureOne(o, c, rig, out));
    if (!c.quiet)
      std::cerr << "  continue " << rig << ": " << benchNumber(rows.back().wall_s, 3) << " s, "
                << verdictOf(rows.back()) << "\n";
  }
  return rows;
}

std::string continueCostCsv(const std::vector<ContinueCostRow>& rows) {
  std::string s = "rig,runs,wall_s,cpu_s,points,timed_out,target_s,load1_min,load1_max,failure\n";
  for (const ContinueCostRow& r : rows)
    s += csvField(r.rig) + "," + std::to_string(r.runs) + "," + benchNumber(r.wall_s, 6) + "," +
         benchNumber(r.cpu_s, 6) + "," + std::to_string(r.points) + "," +
         (r.timed_out ? "1" : "0") + "," + benchNumber(kContinueTargetS, 6) + "," +
         benchNumber(r.load_min, 2, Notation::Fixed) + "," +
         benchNumber(r.load_max, 2, Notation::Fixed) + "," + csvField(r.failure) + "\n";
  return s;
}

std::string continueCostMarkdown(const std::vector<ContinueCostRow>& rows) {
  std::ostringstream os;
  os << "`metrosync continue RIG ... --all` on 2 cores: the whole process's wall time from "
        "outside (median), its CPU time (all threads), the points of branches.csv; target <= "
     << benchNumber(kContinueTargetS, 3) << " s of wall time.\n\n"
     << "| rig | runs | wall | CPU | points | load | verdict |\n|---|---|---|---|---|---|---|\n";
  for (const ContinueCostRow& r : rows)
    os << "| " << r.rig << " | " << r.runs << " | " << (r.timed_out ? "> " : "")
       << benchNumber(r.wall_s, 3) << " s | " << benchNumber(r.cpu_s, 3) << " s | " << r.points
       << " | " << benchNumber(r.load_min, 2, Notation::Fixed) << "-"
       << benchNumber(r.load_max, 2, Notation::Fixed) << " | " << verdictOf(r) << " |\n";
  os << "\nMade by (each with `--out DIR`):\n\n";
  for (const ContinueCostRow& r : rows) os << "    " << r.command << "\n";
  return os.str();
}

}  // namespace metrosync::bench
