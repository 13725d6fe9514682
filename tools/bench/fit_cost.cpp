#include "tools/bench/fit_cost.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "tools/bench/bench_metrics.h"
#include "tools/bench/csv_table.h"
#include "tools/bench/subprocess.h"

namespace metrosync::bench {

namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The fit bench's per-record CSV (fit_recovery.cpp's --csv), by its columns.
std::vector<FitRecordCost> readFits(const fs::path& csv) {
  const CsvTable t = parseCsvTable(slurp(csv), csv.string());
  if (t.columns.empty()) throw std::invalid_argument(csv.string() + ": empty");
  std::vector<FitRecordCost> out;
  for (size_t k = 0; k < t.rows.size(); ++k) {
    FitRecordCost r;
    r.record = std::stoi(t.text(k, "record"));
    r.wall_s = t.number(k, "wall_s");
    r.cpu_s = t.number(k, "cpu_s");
    r.model_runs = std::stol(t.text(k, "model_runs"));
    r.recovered = t.text(k, "recovered") == "1";
    r.error = t.text(k, "error");
    out.push_back(r);
  }
  return out;
}

// The median wall_seconds of `repeat` runs of `rig` (after one not counted); NaN on a failure.
double runSeconds(const FitCostOptions& o, const BenchOptions& c, const fs::path& rig,
                  const fs::path& out) {
  std::vector<double> walls;
  for (int k = 0; k <= o.run_repeat; ++k) {
    waitForLoad(c);
    const ProcessResult pr = runProcess(
        {o.metrosync, "run", rig.string(), "--quiet", "--no-plot", "--out", out.string()});
    std::ifstream in(out / "summary.json");
    if (!pr.ok() || !in) return std::nan("");
    const double w = nlohmann::json::parse(in).value("wall_seconds", std::nan(""));
    fs::remove_all(out);
    if (k > 0) walls.push_back(w);
  }
  return median(walls);
}

std::vector<std::string> fitBenchArgv(const FitCostOptions& o, const fs::path& tmp) {
  return {o.fit_bench,
          "--records",
          std::to_string(o.records),
          "--seed",
          std::to_string(o.seed),
          "--duration",
          benchNumber(o.duration_s, 6),
          "--jobs",
          "1",
          "--keep",
          tmp.string(),
          "--csv",
          (tmp / "fits.csv").string(),
          "--out",
          (tmp / "fit.md").string()};
}

}  // namespace

FitCost measureFitCost(const FitCostOptions& o, const BenchOptions& c) {
  FitCost f;
  const fs::path tmp =
      fs::temp_directory_path() / ("metrosync-bench-fit-" + std::to_string(::getpid()));
  fs::create_directories(tmp);
  const std::vector<std::string> argv = fitBenchArgv(o, tmp);
  f.command = shellCommand(argv);
  f.load_min = f.load_max = waitForLoad(c);
  const ProcessResult pr = runProcess(argv);
  try {
    if (!pr.ok())
      throw std::invalid_argument("the fit bench failed: exit " + std::to_string(pr.exit_code) +
                                  ": " + (pr.err.empty() ? pr.error : pr.err.substr(0, 200)));
    f.records = readFits(tmp / "fits.csv");
    for (FitRecordCost& r : f.records) {
      r.run_s =
          runSeconds(o, c, tmp / ("record" + std::to_string(r.record) + ".yaml"), tmp / "run");
      if (!c.quiet)
        std::cerr << "  fit of record " << r.record << ": " << benchNumber(r.wall_s, 3)
                  << " s wall, one run " << benchNumber(1e3 * r.run_s, 3) << " ms\n";
    }
  } catch (const std::exception& e) {
    f.failure = e.what();
  }
  f.load_max = std::max(f.load_max, loadAverage1());
  fs::remove_all(tmp);
  return f;
}

std::string fitCostCsv(const FitCost& f) {
  std::string s =
      "record,wall_s,cpu_s,model_runs,recovered,run_wall_seconds,fit_over_run,"
      "load1_min,load1_max,failure\n";
  for (const FitRecordCost& r : f.records)
    s += std::to_string(r.record) + "," + benchNumber(r.wall_s, 6) + "," + benchNumber(r.cpu_s, 6) +
         "," + std::to_string(r.model_runs) + "," + (r.recovered ? "1" : "0") + "," +
         benchNumber(r.run_s, 6) + "," + benchNumber(r.wall_s / r.run_s, 6) + "," +
         benchNumber(f.load_min, 2, Notation::Fixed) + "," +
         benchNumber(f.load_max, 2, Notation::Fixed) + "," + csvField(r.error) + "\n";
  if (!f.failure.empty()) s += ",,,,,,,,," + csvField(f.failure) + "\n";
  return s;
}

std::string fitCostMarkdown(const FitCost& f, const FitCostOptions& o) {
  std::ostringstream os;
  if (!f.failure.empty()) return "**The fit was not measured: " + f.failure + ".**\n";
  std::vector<double> wall, cpu, ratio, runs;
  int recovered = 0;
  for (const FitRecordCost& r : f.records)
    wall.push_back(r.wall_s), cpu.push_back(r.cpu_s), ratio.push_back(r.wall_s / r.run_s),
        runs.push_back(static_cast<double>(r.model_runs)), recovered += r.recovered;
  const double w = median(wall), q = median(ratio);
  os << "**One fit: median " << benchNumber(w, 3)
     << " s wall (target <= " << benchNumber(kFitWallTargetS, 3)
     << " s: " << (w <= kFitWallTargetS ? "met" : "NOT met") << "), " << benchNumber(q, 3)
     << "x one run of the same rig (target <= " << benchNumber(kFitOverRunTarget, 3)
     << "x: " << (q <= kFitOverRunTarget ? "met" : "NOT met") << ").**\n\n"
     << f.records.size() << " of the fit bench's records (" << o.records << " asked; the full "
     << "bench has 50) of " << benchNumber(o.duration_s, 3) << " s, seed " << o.seed
     << ", one fit at a time; median CPU " << benchNumber(median(cpu), 3)
     << " s per fit, median model runs " << benchNumber(median(runs), 4) << ", recovered "
     << recovered << " of " << f.records.size() << "; one run: `metrosync run recordI.yaml "
     << "--quiet --no-plot`, median wall_seconds of " << o.run_repeat << ". 1-minute load "
     << benchNumber(f.load_min, 2, Notation::Fixed) << "-"
     << benchNumber(f.load_max, 2, Notation::Fixed)
     << ".\n\n| record | fit wall | fit CPU | model runs | recovered | one run | fit / run |\n"
     << "|---|---|---|---|---|---|---|\n";
  for (const FitRecordCost& r : f.records)
    os << "| " << r.record << " | " << benchNumber(r.wall_s, 3) << " s | "
       << benchNumber(r.cpu_s, 3) << " s | " << r.model_runs << " | "
       << (r.recovered ? "yes" : "no") << " | " << benchNumber(1e3 * r.run_s, 3) << " ms | "
       << benchNumber(r.wall_s / r.run_s, 3) << " |\n";
  os << "\nMade by:\n\n    " << f.command << "\n";
  return os.str();
}

}  // namespace metrosync::bench
