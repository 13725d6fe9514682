#include "tools/cli/basin.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <thread>

#include "sim/analysis/basin.h"
#include "sim/analysis/sweep.h"
#include "sim/record/atomic_file.h"
#include "tools/cli/commands.h"
#include "tools/cli/engines.h"
#include "tools/cli/network_sweep.h"
#include "tools/cli/number_option.h"
#include "tools/cli/option_keys.h"
#include "tools/cli/range_warnings.h"
#include "tools/cli/sweep_point_run.h"
#include "tools/cli/sweep_summary.h"
#include "tools/report/basin_files.h"
#include "tools/report/folder_lock.h"
#include "tools/report/json_file.h"
#include "tools/report/outputs.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

namespace {

namespace fs = std::filesystem;

constexpr long kMaxSamples = 10000000;
// Up to this many keys every corner of the drawn box is loaded before the samples run.
constexpr size_t kMaxCornerKeys = 8;

const std::vector<std::string>& basinFileNames() {
  static const std::vector<std::string> names = {"basin.csv", "basin.json", "basin.png"};
  return names;
}

// What is drawn and run, checked before any file is written.
struct BasinPlan {
  std::vector<RandomKey> keys;
  std::string text;  // the rig's YAML
  std::string rig_name;
  int n = 0;
  std::string model, engine;
  std::string path;
  int jobs = 1;
};

// The overrides of one sample and the texts of its values (the number each text denotes is the
// value the rig gets, as for a sweep's grid points).
std::vector<std::string> sampleOverrides(const BasinPlan& plan, const std::vector<double>& values,
                                         std::vector<std::string>* texts) {
  std::vector<std::string> o;
  for (size_t k = 0; k < plan.keys.size(); ++k) {
    const std::string t = sweepValueText(values[k]);
    if (texts) texts->push_back(t);
    o.push_back(plan.keys[k].key + "=" + t);
  }
  return o;
}

// The rig at the corners of the drawn box (each key at FROM or TO): a bad key or value stops here.
void checkCorners(const BasinOptions& opt, BasinPlan& plan) {
  const size_t k = plan.keys.size();
  std::set<std::vector<bool>> corners;
  if (k <= kMaxCornerKeys) {
    for (long c = 0; c < (1L << k); ++c) {
      std::vector<bool> high(k);
      for (size_t a = 0; a < k; ++a) high[a] = (c >> a) & 1;
      corners.insert(high);
    }
  } else {
    corners.insert(std::vector<bool>(k, false));
    corners.insert(std::vector<bool>(k, true));
  }
  for (const auto& high : corners) {
    std::vector<double> v;
    for (size_t a = 0; a < k; ++a) {
      const RandomKey& r = plan.keys[a];
      v.push_back(r.angle ? wrapToTwoPi(high[a] ? r.to : r.from) : (high[a] ? r.to : r.from));
    }
    const std::vector<std::string> point = sampleOverrides(plan, v, nullptr);
    std::string where;
    for (const auto& p : point) where += (where.empty() ? "" : ", ") + p;
    const auto [model, engine] =
        checkSweepPoint(plan.text, opt.run, point, plan.n, "the start " + where);
    plan.model = model;
    plan.engine = engine;
  }
}

BasinPlan planBasin(const BasinOptions& opt) {
  if (opt.random.empty()) throw UsageError("basin: give at least one --random KEY=FROM:TO");
  if (opt.samples < 1) throw UsageError("basin: give --samples S");  // parsed by its rule
  BasinPlan plan;
  plan.text = sweepRigText(opt.run);
  const std::string name = displayName(opt.run);
  const Rig base = loadSweepRig(plan.text, name, opt.run.sets);
  checkSensibleRanges(plan.text, name, opt.run.sets, opt.run.strict);  // the base rig only
  // the keys resolved against the rig (docs/keys.md), no two setting one rig key
  std::vector<OptionKey> keys;
  for (const auto& r : opt.random)
    keys.push_back(resolveOptionKey({plan.text, name, opt.run.sets}, "--random", r, true));
  refuseSharedKeys(keys);
  for (size_t i = 0; i < keys.size(); ++i)
    plan.keys.push_back(parseRandom(opt.random[i], isPhaseName(keys[i].key.key.leaf())));
  plan.n = static_cast<int>(base.metronomes.size());
  plan.rig_name = base.name;
  checkCorners(opt, plan);
  plan.path = opt.run.out.empty() ? defaultOutputDir(base.name, "basin") : opt.run.out;
  return plan;
}

// The overrides of sample k (its draws depend only on (seed, k)); `texts` the drawn values.
std::vector<std::string> sampleAt(const BasinOptions& opt, const BasinPlan& plan, long k,
                                  std::vector<std::string>* texts) {
  return sampleOverrides(plan, drawSample(plan.keys, opt.seed, k), texts);
}

// Every sample, run by `schedule` (threads, or MPI ranks) on up to --jobs threads; plan.jobs
// becomes the number that ran.
void runSamples(const BasinOptions& opt, BasinPlan& plan, const SweepScheduler& schedule,
                BasinRows& samples) {
  plan.jobs = schedule(
      opt.samples, [](long) { return true; }, opt.run.jobs,
      [&](long k) -> std::optional<SweepPoint> {
        return runSweepPointAt(plan.text, opt.run, sampleAt(opt, plan, k, nullptr), plan.n, k);
      },
      [&](const SweepPoint& p) {  // one at a time (the scheduler's contract)
        std::vector<std::string> texts;
        sampleAt(opt, plan, p.index, &texts);
        samples.add(BasinSample{texts, p});
      },
      [] { return FileSink::stopRequested(); });
}

nlohmann::json basinJson(const BasinOptions& opt, const BasinPlan& plan,
                         const std::vector<RegimeFraction>& fractions,
                         const std::vector<std::string>& files, double wall_s) {
  return {{"command", "basin"},
          {"rig", opt.run.rig_path.empty() ? "<default rig>" : opt.run.rig_path},
          {"rig_name", plan.rig_name},
          {"rig_text", plan.text},
          {"sets", opt.run.sets},
          {"model", plan.model},
          {"engine", plan.engine},
          {"metronomes", plan.n},
          {"seed", opt.seed},
          {"samples", opt.samples},
          {"random", randomKeysJson(plan.keys)},
          {"fractions", fractionsJson(fractions)},
          {"confidence", 0.95},
          {"interval", "Wilson score"},
          {"jobs", plan.jobs},
          {"wall_seconds", wall_s},
          {"files", files}};
}

OutputDir openBasinDir(const std::string& path) {
  try {
    OutputDir d(path);
    d.removeStaleOutputs();
    std::error_code ec;
    for (const auto& name : basinFileNames()) fs::remove(d.file(name), ec);
    return d;
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("--out: ") + e.what());
  }
}

int basinImpl(const BasinOptions& opt, const SweepScheduler& schedule, int ranks) {
  const auto t0 = std::chrono::steady_clock::now();
  BasinPlan plan = planBasin(opt);
  std::optional<FolderLock> lock;
  if (fs::is_directory(plan.path)) lock.emplace(plan.path, "metrosync basin");
  installStopHandlers();
  BasinRows samples;  // streamed to a private temporary folder as they finish
  runSamples(opt, plan, schedule, samples);
  if (FileSink::stopRequested()) {
    std::cerr << "metrosync: error: interrupted by a signal after " << samples.added() << " of "
              << opt.samples << " samples; nothing written\n";
    return kSimulationFailed;
  }
  const OutputDir dir = openBasinDir(plan.path);
  if (!lock) lock.emplace(plan.path, "metrosync basin");
  samples.tally();
  const long failed = samples.failed();
  const std::vector<RegimeFraction> fractions = regimeFractions(samples.regimes());
  samples.writeCsv(dir.file("basin.csv"), plan.keys, plan.n);
  std::vector<std::string> files = {"basin.csv"};
  const std::string title = plan.rig_name + " - " + modelTitle(plan.model) + ", " +
                            std::to_string(opt.samples) + " random starts (seed " +
                            std::to_string(opt.seed) + ")";
  if (!opt.no_plot && plotBasinMap(dir, plan.keys, samples, title)) files.push_back("basin.png");
  files.push_back("basin.json");
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  writeJsonFile(dir.file("basin.json"), basinJson(opt, plan, fractions, files, wall_s));
  if (!opt.run.quiet) {
    std::cout << "basin stability of " << plan.rig_name << " (" << modelTitle(plan.model) << ", "
              << plan.n << (plan.n == 1 ? " metronome" : " metronomes") << "), seed " << opt.seed
              << ", " << opt.samples << " samples on "
              << (ranks > 1 ? std::to_string(ranks) + " MPI ranks x " : std::string()) << plan.jobs
              << (plan.jobs == 1 ? " thread" : " threads") << ":\n"
              << fractionsTable(fractions, opt.samples) << "files: " << dir.path() << "/ (";
    for (size_t k = 0; k < files.size(); ++k) std::cout << (k ? ", " : "") << files[k];
    std::cout << ")\n";
  }
  if (failed > 0)
    std::cerr << "metrosync: warning: " << failed
              << " samples failed (regime 'failed', counted in the fractions)\n";
  return kSuccess;
}

}  // namespace

CLI::App* addBasinCommand(CLI::App& app, BasinOptions& opt) {
  CLI::App* c = app.add_subcommand(
      "basin",
      "basin stability: the fraction of random starts ending in each regime, with 95% "
      "Wilson intervals");
  c->add_option("RIG", opt.run.rig_path,
                "rig file (YAML, docs/contract.md section 1); default: the built-in rig");
  c->add_option("--random", opt.random,
                "a rig key drawn uniformly from FROM to TO for each sample; a phase (a key "
                "ending in phi or psi) on the circle, wrapped to [0, 2 pi). "
                "Values may use pi: --random metronomes.0.start.phi=0:2pi --random "
                "metronomes.1.start.A=1:4. Repeatable")
      ->type_name("KEY=FROM:TO")
      ->required()
      ->allow_extra_args(false);
  addInteger(c, "--samples", opt.samples, 1, kMaxSamples, "how many random starts")
      ->type_name("S")
      ->required();
  addSeed(c, "--seed", opt.seed,
          "the seed of the draws (default 1): sample k's values depend only on the seed "
          "and k, not on --jobs");
  c->add_option("--set", opt.run.sets, "override a rig key for every sample; repeatable")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  c->add_option("--model", opt.run.model, "slow: the slow flow (default); full: the full model")
      ->check(CLI::IsMember({"slow", "full"}));
  c->add_option("--engine", opt.run.engine, "the engine of the full model (as for sweep)");
  addInteger(c, "--jobs", opt.run.jobs, 1, kMaxJobs,
             "worker threads (default: the number of cores; never more than the samples)");
  c->add_option("--out", opt.run.out, "output directory (default: runs/<rig name>-basin)")
      ->type_name("DIR");
  addStrictFlag(c, opt.run.strict);
  c->add_flag("--no-plot", opt.no_plot, "no basin.png");
  c->add_flag("-q,--quiet", opt.run.quiet, "no table on stdout");
  c->footer(
      "Files in --out DIR: basin.csv (sample, the drawn values, regime, A_1..A_N, psi_2..psi_N, "
      "complete), basin.json (what was drawn; each regime's count, fraction and 95% Wilson "
      "interval), basin.png (two --random keys: the samples coloured by regime).\n"
      "Exit codes: 0 success; 2 bad command line or rig (nothing written); 3 interrupted "
      "(nothing written); 1 anything else.");
  return c;
}

int basinCommand(const BasinOptions& opt) {
  const SweepScheduler threads = [](long size, const std::function<bool(long)>& wanted, int jobs,
                                    const SweepPointRunner& run, const SweepPointSink& finished,
                                    const std::function<bool()>& stop) {
    return runSweepPoints(size, wanted, jobs, run, finished, stop);
  };
  return basinCommand(opt, threads, 1);
}

int basinCommand(const BasinOptions& opt, const SweepScheduler& schedule, int ranks) {
  try {
    return basinImpl(opt, schedule, ranks);
  } catch (const SweepInputError& e) {
    throw UsageError(e.what());
  } catch (const FolderLockedError& e) {
    throw UsageError(e.what());
  }
}

SweepPointRunner basinSampleRunner(const BasinOptions& opt) {
  try {
    auto plan = std::make_shared<const BasinPlan>(planBasin(opt));
    return [plan, opt](long k) {
      return runSweepPointAt(plan->text, opt.run, sampleAt(opt, *plan, k, nullptr), plan->n, k);
    };
  } catch (const SweepInputError& e) {
    throw UsageError(e.what());
  }
}

}  // namespace metrosync::cli
