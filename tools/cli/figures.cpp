#include "tools/cli/figures.h"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <thread>

#include "tools/cli/commands.h"
#include "tools/cli/engines.h"
#include "tools/cli/number_option.h"
#include "tools/cli/sweep.h"
#include "tools/cli/validate.h"
#include "tools/report/figures.h"
#include "tools/report/outputs.h"
#include "tools/report/sweep_files.h"

namespace metrosync::cli {

namespace {

namespace fs = std::filesystem;

const char* kMapId = "exp1";

std::vector<std::string> allIds() {
  std::vector<std::string> ids;
  for (const auto& f : paperFigureSpecs()) ids.push_back(f.id);
  ids.push_back(kMapId);
  return ids;
}

bool wanted(const FiguresOptions& opt, const std::string& id) {
  return opt.only.empty() || std::find(opt.only.begin(), opt.only.end(), id) != opt.only.end();
}

const Engine& fullEngine(const std::string& requested) {
  const Engine* e = findEngine(requested);
  if (e && e->model() != "full")
    throw UsageError("--engine " + requested +
                     ": the full model's engines: " + engineNames("full"));
  try {
    return selectEngine(requested, "full", "");
  } catch (const EngineSelectionError& e) {
    throw UsageError(std::string("figures: ") + e.what());
  }
}

std::vector<std::string> mapModels(const FiguresOptions& opt) {
  if (opt.model == "both") return {"slow", "full"};
  return {opt.model};
}

// The computed exp1 in one model: `metrosync sweep` into DIR/<name>-sweep, read back.
// Returns the sweep's exit code.
int runMap(const FiguresOptions& opt, const std::string& rigs_dir, const OutputDir& dir,
           const std::string& model, int jobs, std::vector<RegimeMapResult>& maps) {
  RegimeMapResult m;
  m.spec = regimeMapSpec(opt.quick);
  m.model = model;
  m.name = opt.model == "both" ? std::string(kMapId) + "-" + model : kMapId;
  m.sweep_dir = m.name + "-sweep";
  SweepOptions so;
  so.rig_path = (fs::path(rigs_dir) / m.spec.rig_file).string();
  so.vary = m.spec.vary();
  so.out = dir.file(m.sweep_dir);
  so.quiet = true;
  so.no_plot = true;
  so.model = model;
  so.engine = model == "full" ? opt.engine : "";
  so.jobs = jobs;
  const int code = sweepCommand(so);
  std::vector<SweepAxis> axes;
  for (const auto& v : so.vary) axes.push_back(parseVary(v));
  m.grid = SweepGrid(std::move(axes));
  m.points = readRegimesCsv(so.out + "/regimes.csv", m.grid, 2).points;
  m.complete = static_cast<long>(m.points.size()) == m.grid.size();
  maps.push_back(std::move(m));
  return code;
}

double scaledMu(const std::vector<Scenario>& scenarios, const std::string& name) {
  for (const auto& s : scenarios)
    if (s.spec.name == name) return s.scaled.friction.valueOr("mu", 0.0);
  return -1;
}

}  // namespace

CLI::App* addFiguresCommand(CLI::App& app, FiguresOptions& opt) {
  CLI::App* cmd = app.add_subcommand(
      "figures",
      "the paper's section-4 figures (f4.1-f4.4) and the experiment's regime diagram (exp1) "
      "computed, as PNG and SVG, with an index figures.md");
  cmd->add_option("--out", opt.out, "output directory")->type_name("DIR")->capture_default_str();
  cmd->add_option("--model", opt.model,
                  "slow: the slow flow, as the paper; full: the full model at the rig's epsilon; "
                  "both: the full model (solid) over the slow flow (dashed), and both maps")
      ->check(CLI::IsMember({"slow", "full", "both"}))
      ->capture_default_str();
  cmd->add_option("--only", opt.only,
                  "make only this figure (f4.1, f4.2, f4.3, f4.4, exp1); "
                  "repeatable")
      ->type_name("ID")
      ->check(CLI::IsMember(allIds()))
      ->allow_extra_args(false);
  cmd->add_flag("--quick", opt.quick, "a 12 x 12 regime map instead of 40 x 40 (f4.x unchanged)");
  cmd->add_option("--rigs", opt.rigs,
                  "the shipped rigs' directory (default: as `validate` finds it)")
      ->type_name("DIR");
  addInteger(cmd, "--jobs", opt.jobs, 1, kMaxJobs,
             "runs at once (default: one per hardware thread)");
  cmd->add_option("--engine", opt.engine, "the full model's engine")->capture_default_str();
  cmd->add_flag("-q,--quiet", opt.quiet, "no progress on stdout");
  cmd->footer(
      "Files in --out DIR: f4.1 .. f4.4 and exp1 (exp1-slow, exp1-full with --model both) as "
      ".png and .svg, figures.md (each figure, its caption, the command that makes it alone), "
      "figures.json (every run's final state and regime), exp1*-sweep/ (the map's sweep).\n"
      "Exit codes: 0 success; 2 bad command line or rigs (nothing written); 3 a run failed or "
      "was interrupted (the figures are still written); 1 anything else.");
  return cmd;
}

int figuresCommand(const FiguresOptions& opt) {
  const std::string rigs_dir = findRigsDir(opt.rigs);
  const std::vector<Scenario> scenarios = loadScenarios(rigs_dir);
  const Engine* engine = &fullEngine(opt.engine);
  std::unique_ptr<OutputDir> dir;
  try {
    dir = std::make_unique<OutputDir>(opt.out);
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("--out: ") + e.what());
  }
  const int jobs =
      opt.jobs > 0 ? opt.jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  auto progress = [&](const std::string& line) {
    if (!opt.quiet) std::cout << "figures: " << line << std::endl;
  };
  std::vector<FigureSpec> specs;
  for (const auto& f : paperFigureSpecs())
    if (wanted(opt, f.id)) specs.push_back(f);
  ValidationEngines engines;
  engines.full_model = [engine](const Rig& rig, RunSink& sink) { return engine->run(rig, sink); };
  FigureModels models{opt.model != "full", opt.model != "slow"};
  const std::vector<FigureResult> figures =
      runPaperFigures(specs, scenarios, engines, models, jobs, progress);

  std::vector<RegimeMapResult> maps;
  int code = kSuccess;
  if (wanted(opt, kMapId))
    for (const auto& model : mapModels(opt)) {
      progress(std::string(kMapId) + ": sweep of the " + model + " model");
      code = std::max(code, runMap(opt, rigs_dir, *dir, model, jobs, maps));
    }
  FiguresContext ctx;
  ctx.models = opt.model;
  ctx.options = opt.quick ? " --quick" : "";
  for (const char* name : {"experiment-low-friction-inphase", "experiment-high-friction-inphase"})
    if (const double mu = scaledMu(scenarios, name); mu >= 0) ctx.mu_experiment.push_back(mu);
  const std::vector<std::string> files = writeFigures(*dir, figures, maps, ctx);

  int failed = 0;
  for (const auto& f : figures)
    for (const auto& r : f.runs)
      failed += (r.has_slow && !r.slow.report.complete) + (r.has_full && !r.full.report.complete);
  if (!opt.quiet) {
    std::cout << "figures: " << files.size() << " files in " << dir->path() << "/ (";
    for (size_t k = 0; k < files.size(); ++k) std::cout << (k ? ", " : "") << files[k];
    std::cout << ")\n";
  }
  if (failed > 0 || code != kSuccess) {
    std::cerr << "metrosync: error: figures: " << failed << " runs failed"
              << (code != kSuccess ? ", the regime map's sweep did not complete" : "") << "\n";
    return kSimulationFailed;
  }
  return kSuccess;
}

}  // namespace metrosync::cli
