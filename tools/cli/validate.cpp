#include "tools/cli/validate.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <thread>

#include "contact/simbody/driven_coulomb.h"
#include "sim/analysis/validation/validation.h"
#include "sim/engines/simbody_plugin.h"
#include "tools/cli/commands.h"
#include "tools/cli/engines.h"
#include "tools/cli/number_option.h"
#include "tools/report/outputs.h"
#include "tools/report/validation_report.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

namespace {

namespace fs = std::filesystem;

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", &tm);
  return buf;
}

// the files an earlier validate left in DIR (the set of disagreement plots varies run to run)
void removeStaleReport(const std::string& dir) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    const bool ours = name == "report.md" || name == "summary.json" || name == "betas.png" ||
                      name == "convergence.png" || name == "sweep.png" ||
                      (name.rfind("disagreement-", 0) == 0 && e.path().extension() == ".png");
    if (ours) fs::remove(e.path(), ec);
  }
}

}  // namespace

CLI::App* addValidateCommand(CLI::App& app, ValidateOptions& opt) {
  CLI::App* cmd = app.add_subcommand(
      "validate",
      "validate the full model against the asymptotics: beta1, beta2 against the Coulomb "
      "element, the paper's eight simulations, convergence in epsilon, where the asymptotics "
      "fail, the experiment's regime sequence, the bifurcations of both models, the paper's "
      "experiments in each variant of the rig; writes report.md with plots");
  cmd->add_option("--out", opt.out, "output directory")->type_name("DIR")->capture_default_str();
  cmd->add_flag("--quick", opt.quick,
                "the reduced plan (fewer drive strengths, two convergence scenarios, the rigs' "
                "own epsilon only, six friction values): a fraction of the full plan's time "
                "(both measured: README.md, Validation)");
  cmd->add_option("--rigs", opt.rigs,
                  "the shipped rigs' directory (default: yaml/rigs under the working directory, "
                  "else above the executable)")
      ->type_name("DIR");
  addInteger(cmd, "--jobs", opt.jobs, 1, kMaxJobs,
             "simulations run at once (default: one per hardware thread); the results do not "
             "depend on it");
  cmd->add_option("--engine", opt.engine, fullEngineHelp() + "; validate's default: direct")
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", opt.quiet, "no progress on stdout");
  cmd->footer(
      "Files in --out DIR: report.md (tables, the command that made it), betas.png, "
      "convergence.png, disagreement-<scenario>.png, sweep.png, summary.json (every number).\n"
      "Exit codes: 0 every check passed; 1 a check failed (see report.md); 2 bad command line or "
      "rig; 3 a simulation stopped early (the report is still written).");
  return cmd;
}

namespace {

// The full model's engine at its default integrator: the runs are rebuilt from the scaled
// parameters (rigAtEpsilon), so the rigs' own simulation keys do not reach it.
const Engine& validationEngine(const std::string& requested) {
  const Engine* e = findEngine(requested);
  if (e && e->model() != "full")
    throw UsageError("--engine " + requested + ": validate runs the full model against the slow " +
                     "flow; the full model's engines: " + engineNames("full"));
  try {
    return selectEngine(requested, "full", "");
  } catch (const EngineSelectionError& e) {
    throw UsageError(std::string("validate: ") + e.what());
  }
}

}  // namespace

// The shipped rigs: --rigs DIR, else yaml/rigs under the working directory, else next to the
// executable (build directories sit in the source tree: <src>/build/metrosync), else where
// `cmake --install` and the Debian package put them (<prefix>/share/metrosync/rigs beside
// <prefix>/bin/metrosync).
std::string findRigsDir(const std::string& given) {
  const std::string probe = shippedScenarios().front().file;
  auto ok = [&](const fs::path& d) {
    std::error_code ec;
    return fs::is_regular_file(d / probe, ec);
  };
  if (!given.empty()) {
    if (!ok(given))
      throw UsageError("--rigs " + given + ": not the shipped rigs (no " + probe + " in it)");
    return given;
  }
  std::vector<fs::path> candidates = {fs::path("yaml/rigs")};
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec)
    for (fs::path d = exe.parent_path(); !d.empty() && d != d.root_path(); d = d.parent_path())
      candidates.push_back(d / "yaml/rigs");
  if (!ec) candidates.push_back(exe.parent_path().parent_path() / "share/metrosync/rigs");
  for (const auto& c : candidates)
    if (ok(c)) return c.string();
  throw UsageError("cannot find the shipped rigs (yaml/rigs/" + probe +
                   ") under the working directory, above the executable or in its installation's "
                   "share/metrosync/rigs; run from the repository root or give --rigs DIR");
}

// The shipped scenarios' scaled parameters; a bad rig throws RigError naming its file.
std::vector<Scenario> loadScenarios(const std::string& rigs_dir) {
  std::vector<Scenario> scenarios;
  for (const auto& spec : shippedScenarios()) {
    const Rig rig = loadRigFile((fs::path(rigs_dir) / spec.file).string());
    Scenario sc;
    sc.spec = spec;
    try {
      sc.scaled = computeScaled(rig);
    } catch (const std::invalid_argument& e) {
      throw RigError(spec.file + ": " + e.what());
    }
    scenarios.push_back(sc);
  }
  return scenarios;
}

int validateCommand(const ValidateOptions& opt) {
  const std::string rigs_dir = findRigsDir(opt.rigs);
  const Engine* engine = &validationEngine(opt.engine);
  const std::vector<Scenario> scenarios = loadScenarios(rigs_dir);
  // the directory only now that every rig is good (SPEC 5: a bad rig writes nothing)
  std::unique_ptr<OutputDir> dir;
  try {
    dir = std::make_unique<OutputDir>(opt.out);
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("--out: ") + e.what());
  }
  removeStaleReport(dir->path());

  ValidationEngines engines;
  engines.full_model = [engine](const Rig& rig, RunSink& sink) { return engine->run(rig, sink); };
  engines.coulomb_probe = [](double s) { return simbodyPlugin().coulomb_probe(s); };
  engines.load_rig = [rigs_dir](const std::string& file, const std::vector<std::string>& sets) {
    return loadRigFile((fs::path(rigs_dir) / file).string(), sets);
  };

  const auto t0 = std::chrono::steady_clock::now();
  auto progress = [&](const std::string& line) {
    if (opt.quiet) return;
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    char stamp[32];
    std::snprintf(stamp, sizeof stamp, "[%6.0f s] ", t);
    std::cout << stamp << line << std::endl;
  };
  const ValidationPlan plan = defaultValidationPlan(opt.quick);
  const int jobs =
      opt.jobs > 0 ? opt.jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  progress("validate: " + std::string(opt.quick ? "quick" : "full") + " plan, full model on the " +
           engine->name() + " engine, rigs from " + rigs_dir + ", " + std::to_string(jobs) +
           " jobs");
  const ValidationResults res = runValidation(plan, scenarios, engines, progress, jobs);

  ReportContext ctx;
  // the command that regenerates the report (--jobs and --quiet do not change it)
  ctx.command = std::string("metrosync validate") + (opt.quick ? " --quick" : "") + " --engine " +
                engine->name() + " --out " + opt.out +
                (opt.rigs.empty() ? "" : " --rigs " + opt.rigs);
  ctx.rigs_dir = rigs_dir;
  ctx.date = utcNow();
  ctx.engine = engine->name();
  const std::vector<std::string> files = writeValidationReport(*dir, res, ctx);

  const int failed = res.failedChecks(), incomplete = res.incompleteRuns();
  if (!opt.quiet) {
    std::cout << "validate (full model on the " << engine->name() << " engine): " << failed
              << " checks failed, " << incomplete << " runs stopped early, wall time "
              << res.wall_seconds << " s\nfiles: " << dir->path() << "/ (";
    for (size_t k = 0; k < files.size(); ++k) std::cout << (k ? ", " : "") << files[k];
    std::cout << ")\n";
  }
  if (incomplete > 0) {
    std::cerr << "metrosync: error: validate: " << incomplete << " simulations stopped early (see "
              << dir->file("report.md") << ")\n";
    return kSimulationFailed;
  }
  if (failed > 0) {
    std::cerr << "metrosync: error: validate: " << failed << " checks failed (see "
              << dir->file("report.md") << ")\n";
    return kOtherError;
  }
  return kSuccess;
}

}  // namespace metrosync::cli
