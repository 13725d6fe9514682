// sweep and basin for Python: the CLI's point runner (tools/cli/sweep.h, basin.h) on threads,
// every point kept in memory; with `out` the CLI's own command writes its files, its points
// collected here as they finish.
#include <pybind11/stl.h>

#include <map>
#include <thread>

#include "sim/analysis/basin.h"
#include "sim/analysis/sweep.h"
#include "tools/cli/basin.h"
#include "tools/cli/commands.h"
#include "tools/cli/engines.h"
#include "tools/cli/network_sweep.h"
#include "tools/cli/option_keys.h"
#include "tools/cli/sweep.h"
#include "tools/cli/sweep_summary.h"
#include "tools/python/bindings.h"
#include "tools/report/basin_files.h"
#include "tools/report/outputs.h"
#include "tools/report/sweep_files.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync::python {

namespace {

namespace cli = metrosync::cli;
using Points = std::map<long, SweepPoint>;

cli::SweepOptions gridOptions(const RigSource& rig, const std::string& model,
                              const std::string& engine, int jobs,
                              const std::optional<std::string>& out) {
  cli::SweepOptions o;
  o.rig_path = rig.path;
  o.rig_text = rig.text;
  o.sets = rig.sets;
  o.model = model;
  o.engine = engine;
  o.jobs = jobs > 0 ? jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  o.quiet = true;
  o.out = out.value_or("");
  o.no_plot = !out;
  return o;
}

// The swept rig before any point's keys: its text, name and metronome count.
struct BaseRig {
  std::string text, name;
  int n = 0;
};

BaseRig baseRig(const cli::SweepOptions& o) {
  BaseRig b;
  b.text = cli::sweepRigText(o);
  const Rig rig = cli::loadSweepRig(b.text, o.rig_path, o.sets);
  b.name = rig.name;
  b.n = static_cast<int>(rig.metronomes.size());
  return b;
}

// A scheduler on threads (runSweepPoints) that also keeps every finished point in `points`.
cli::SweepScheduler collecting(Points& points) {
  return [&points](long size, const std::function<bool(long)>& wanted, int jobs,
                   const cli::SweepPointRunner& run, const cli::SweepPointSink& finished,
                   const std::function<bool()>& stop) {
    return runSweepPoints(
        size, wanted, jobs, run,
        [&](const SweepPoint& p) {
          finished(p);
          points[p.index] = p;
        },
        stop);
  };
}

// Runs every index below `size` with `run` (no folder), keeping the points.
void runInMemory(long size, int jobs, const cli::SweepPointRunner& run, Points& points) {
  cli::installStopHandlers();
  collecting(points)(
      size, [](long) { return true; }, jobs, run, [](const SweepPoint&) {},
      [] { return FileSink::stopRequested(); });
}

// The points' numbers as a table (A_1..A_N, psi_2..psi_N, r, s, tau, in_phase_fraction, complete,
// index: regimes.csv's numbers before printing) and their texts.
py::dict pointsToPython(const Points& points, int n) {
  ColumnTable t;
  for (int i = 1; i <= n; ++i) t.names.push_back("A_" + std::to_string(i));
  for (int j = 2; j <= n; ++j) t.names.push_back("psi_" + std::to_string(j));
  for (const char* c : {"r", "s", "tau", "in_phase_fraction", "complete", "index"})
    t.names.push_back(c);
  std::vector<std::string> regime, clusters, message;
  for (const auto& [g, p] : points) {
    t.values.insert(t.values.end(), p.A.begin(), p.A.end());
    t.values.insert(t.values.end(), p.psi.begin(), p.psi.end());
    t.values.insert(t.values.end(), {p.r, p.s, p.tau, p.in_phase_fraction, p.complete ? 1.0 : 0.0,
                                     static_cast<double>(g)});
    regime.push_back(p.regime);
    clusters.push_back(p.clusters);
    message.push_back(p.message);
  }
  py::dict d;
  d["numbers"] = tableToPython(std::move(t));
  d["regime"] = regime;
  d["clusters"] = clusters;
  d["message"] = message;
  return d;
}

SweepManifest sweepManifest(const cli::SweepOptions& o, const BaseRig& base,
                            const SweepGrid& grid) {
  SweepManifest m;
  const auto [model, engine] =
      cli::checkSweepPoint(base.text, o, grid.overrides(0), base.n, "grid point 0");
  m.model = model;
  m.engine = engine;
  m.rig_path = o.rig_path;
  m.rig_name = base.name;
  m.rig_text = base.text;
  m.sets = o.sets;
  m.metronomes = base.n;
  m.grid = grid;
  return m;
}

// `sweep`: {"points": pointsToPython, "grid": the grid's JSON, "summary": sweep.json's status}.
py::dict sweep(const RigSource& rig, const std::vector<std::string>& vary, const std::string& model,
               const std::string& engine, int jobs, const std::optional<std::string>& out) {
  cli::SweepOptions o = gridOptions(rig, model, engine, jobs, out);
  o.vary = vary;
  Points points;
  SweepManifest m;
  runReleased([&] {
    const cli::SweepPointRunner run = cli::sweepPointRunner(o);  // the CLI's checks, or throws
    std::vector<SweepAxis> axes;
    for (const std::string& v : vary) axes.push_back(parseVary(v));
    m = sweepManifest(o, baseRig(o), SweepGrid(std::move(axes)));
    if (out)
      cli::sweepCommand(o, collecting(points), 1);
    else
      runInMemory(m.grid.size(), o.jobs, run, points);
  });
  nlohmann::json status = cli::statusJson(m, m.grid.size(), cli::tallyOf(points),
                                          static_cast<long>(points.size()) == m.grid.size());
  status["jobs"] = o.jobs;
  // every axis's values, also those sweep.json leaves out (kMaxListedAxisValues): the result's
  // .values (the points are in memory already)
  for (std::size_t a = 0; a < m.grid.axes().size(); ++a) {
    const SweepAxis& axis = m.grid.axes()[a];
    std::vector<std::string> texts;
    for (long k = 0; k < axis.count; ++k) texts.push_back(axis.text(k));
    status["grid"]["axes"][a]["values"] = texts;
  }
  py::dict d;
  d["points"] = pointsToPython(points, m.metronomes);
  d["summary"] = status.dump();
  return d;
}

// basin.json's account of the draws and their fractions (without the run's timings and files).
nlohmann::json basinSummary(const cli::BasinOptions& b, const BaseRig& base,
                            const std::vector<RandomKey>& keys, const Points& points) {
  std::vector<std::string> regimes;
  for (const auto& [k, p] : points) regimes.push_back(p.regime);
  const auto [model, engine] = cli::checkSweepPoint(base.text, b.run, {}, base.n, "the rig");
  return {{"command", "basin"},
          {"rig", b.run.rig_path},
          {"rig_name", base.name},
          {"sets", b.run.sets},
          {"model", model},
          {"engine", engine},
          {"metronomes", base.n},
          {"seed", b.seed},
          {"samples", b.samples},
          {"random", randomKeysJson(keys)},
          {"fractions", fractionsJson(regimeFractions(regimes))},
          {"confidence", 0.95},
          {"interval", "Wilson score"},
          {"jobs", b.run.jobs}};
}

// The values each sample drew, as the rig got them (the numbers their texts denote).
ColumnTable drawnValues(const std::vector<RandomKey>& keys, std::uint64_t seed,
                        const Points& points) {
  ColumnTable t;
  for (const RandomKey& k : keys) t.names.push_back(k.key);
  for (const auto& [k, p] : points)
    for (double v : drawSample(keys, seed, k)) t.values.push_back(std::stod(sweepValueText(v)));
  return t;
}

// `basin`: {"points", "drawn": (keys, array), "summary": basin.json's account}.
py::dict basin(const RigSource& rig, const std::vector<std::string>& random, long samples,
               std::uint64_t seed, const std::string& model, const std::string& engine, int jobs,
               const std::optional<std::string>& out) {
  cli::BasinOptions b;
  b.run = gridOptions(rig, model, engine, jobs, out);
  b.random = random;
  b.samples = samples;
  b.seed = seed;
  b.no_plot = !out;
  Points points;
  std::vector<RandomKey> keys;
  nlohmann::json summary;
  runReleased([&] {
    const cli::SweepPointRunner run = cli::basinSampleRunner(b);  // the CLI's checks, or throws
    const std::string text = cli::sweepRigText(b.run);            // the keys as basin resolves them
    for (const std::string& r : random) {
      const cli::OptionKey k =
          cli::resolveOptionKey({text, b.run.rig_path, b.run.sets}, "--random", r, true);
      keys.push_back(parseRandom(r, isPhaseName(k.key.key.leaf())));
    }
    if (out)
      cli::basinCommand(b, collecting(points), 1);
    else
      runInMemory(samples, b.run.jobs, run, points);
    summary = basinSummary(b, baseRig(b.run), keys, points);
  });
  py::dict d;
  d["points"] = pointsToPython(points, summary["metronomes"].get<int>());
  d["drawn"] = tableToPython(drawnValues(keys, seed, points));
  d["summary"] = summary.dump();
  return d;
}

}  // namespace

void bindGrids(py::module_& m) {
  m.def("sweep", &sweep, py::arg("rig"), py::arg("vary"), py::arg("model") = "",
        py::arg("engine") = "", py::arg("jobs") = 0, py::arg("out") = std::nullopt);
  m.def("basin", &basin, py::arg("rig"), py::arg("random"), py::arg("samples"), py::arg("seed") = 1,
        py::arg("model") = "", py::arg("engine") = "", py::arg("jobs") = 0,
        py::arg("out") = std::nullopt);
}

}  // namespace metrosync::python
