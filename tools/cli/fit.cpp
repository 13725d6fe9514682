#include "tools/cli/fit.h"

#include <cmath>
#include <cstdio>
#include <iostream>

#include "base/number_text.h"
#include "sim/analysis/fit/ceres_plugin.h"
#include "sim/analysis/fit/fit_strategy.h"
#include "sim/analysis/fit/model_samples.h"
#include "sim/analysis/fit/start_guess.h"
#include "tools/cli/commands.h"
#include "tools/cli/engines.h"
#include "tools/cli/fit_inputs.h"
#include "tools/cli/number_option.h"
#include "tools/cli/option_keys.h"
#include "tools/cli/range_warnings.h"
#include "tools/report/json_file.h"
#include "yaml/key_path.h"
#include "yaml/rig_loader.h"
#include "yaml/rig_writer.h"

namespace metrosync::cli {

namespace {

// --starts: each start is a whole search over growing windows (seconds to minutes); more than
// this is a typo, not a budget.
constexpr int kMaxStarts = 1000;

const char* kFitExitCodes =
    "Exit codes: 0 fitted; 2 bad command line, rig or data file (nothing written); 3 the model "
    "fails at the starting values; 1 anything else.";

// Is a rig key of `paths` (or a map above one) set by one of the --set overrides?
bool givenBySet(const FitOptions& opt, const std::string& text, const std::vector<KeyPath>& paths) {
  for (const std::string& set : opt.sets) {
    const RigKey k = resolveRigKey(text, opt.rig_path, opt.sets, keyTextOf(set), "--set " + set);
    if (!sharedPath(paths, k.paths).empty()) return true;
  }
  return false;
}

// Keys that cannot be negative are bounded at 0; a start value of 0 gets a typical scale.
void boundsOf(FreeParameter& p, const KeyPath& key) {
  const std::string& last = key.leaf();
  const std::string parent = key.parent();
  for (const char* k : {"damping", "decay_rate", "mu", "c", "impulse", "k", "inertia", "mass",
                        "box_mass", "steady_amplitude", "length"})
    if (last == k) p.lower = 0.0;
  if (last == "angle" && parent == "escapement") p.lower = 0.0;
  if (parent == "friction") p.lower = 0.0;  // every law parameter is >= 0 (contact/law_kind.h)
  double typical = 1.0;                     // rad/s, and anything else
  if (parent == "start")
    typical = (last == "angle") ? 0.1 : (last == "x" || last == "v") ? 0.01 : 1.0;
  p.scale = p.start != 0.0 ? std::abs(p.start) : typical;
  p.size_floor = p.lower >= 0 ? 0.0 : p.scale;
}

// Where a key's start comes from: a --set (used as given), else a section-3 shortcut where one
// applies, else the rig (0 for an absent start key). Checks that the key can be set to a number.
// A --set start keeps its value and the shortcut goes to `shortcut` (a further starting point).
double startOfKey(const KeyPath& key, const std::string& text, const FitOptions& opt,
                  const Rig& rig, const MeasuredData& data, std::string& from,
                  std::optional<double>& shortcut) {
  const std::string& path = key.text();  // names and indices only
  std::optional<double> v = rigNumber(text, opt.rig_path, opt.sets, path);
  from = givenBySet(opt, text, {key}) ? "--set" : "rig";
  if (!v) {
    if (key.parent() != "start")
      throw UsageError("--free " + path + ": the rig gives no value for it (free the key the " +
                       "rig gives: damping or decay_rate, impulse or steady_amplitude, as " +
                       "written in " + opt.rig_path + ")");
    v = 0.0;
    from = "default";
  }
  if (const std::optional<StartGuess> g = section3Guess(path, rig, data)) {
    if (from == "--set") {
      shortcut = g->value;
    } else {
      v = g->value;
      from = g->from;
    }
  }
  std::vector<std::string> sets = opt.sets;
  sets.push_back(path + "=" + exactNumberText(*v));
  loadRigText(text, opt.rig_path, sets);  // the key takes this value
  return *v;
}

// One free parameter: the rig keys a --free key stands for (every metronome's for
// metronomes.*.X: one shared value) and their mean start.
FreeParameter freeParameter(const OptionKey& k, const std::string& text, const FitOptions& opt,
                            const Rig& rig, const MeasuredData& data, std::string& from) {
  FreeParameter p;
  p.name = k.key.key.text();
  double sum = 0.0, shortcuts = 0.0;  // shortcuts: the shortcut's value, else the start
  bool differ = false, any_shortcut = false;
  for (std::size_t i = 0; i < k.key.paths.size(); ++i) {
    std::string f;
    std::optional<double> g;
    const double v = startOfKey(k.key.paths[i], text, opt, rig, data, f, g);
    differ = differ || (i > 0 && v != sum / i);
    from = i == 0 || f == from ? f : "mixed";
    sum += v;
    shortcuts += g.value_or(v);
    any_shortcut = any_shortcut || g.has_value();
    p.keys.push_back(k.key.paths[i].text());
  }
  p.start = sum / p.keys.size();
  if (any_shortcut) p.shortcut = shortcuts / p.keys.size();
  if (differ) from = "mean of " + from + " values";
  boundsOf(p, k.key.paths.front());
  return p;
}

// The free parameters: each --free key resolved by the one key resolver (docs/keys.md), two
// that set one rig key refused.
std::vector<FreeParameter> freeParameters(const FitOptions& opt, const std::string& text,
                                          const Rig& rig, const MeasuredData& data,
                                          std::vector<std::string>& start_from) {
  std::vector<OptionKey> keys;
  for (const std::string& k : opt.free)
    keys.push_back(resolveOptionKey({text, opt.rig_path, opt.sets}, "--free", k, false));
  refuseSharedKeys(keys);
  std::vector<FreeParameter> free;
  for (const OptionKey& k : keys) {
    if (k.key.paths.empty()) throw UsageError(k.typed + ": the key stands for no rig key");
    std::string from;
    free.push_back(freeParameter(k, text, opt, rig, data, from));
    start_from.push_back(from);
  }
  return free;
}

std::vector<std::string> withValues(const FitOptions& opt, const std::vector<FreeParameter>& free,
                                    const std::vector<double>& v) {
  std::vector<std::string> sets = opt.sets;
  for (std::size_t j = 0; j < free.size(); ++j)
    for (const std::string& key : free[j].keys) sets.push_back(key + "=" + exactNumberText(v[j]));
  return sets;
}

std::string fittedRig(const FitOptions& opt, const std::string& text, const FitReport& rep) {
  const FitOutcome& r = rep.outcome;
  std::string keys, held;
  for (std::size_t j = 0; j < rep.free.size(); ++j) {
    keys += (keys.empty() ? "" : ", ") + rep.free[j].name;
    if (!r.identifiable[j]) held += (held.empty() ? "" : ", ") + rep.free[j].name;
  }
  std::vector<std::string> header = {
      "Fitted by metrosync " + std::string(metrosyncVersion()) + " fit: rig " + opt.rig_path +
          ", data " + opt.data_path + ", " + opt.model + " model",
      "free: " + keys + " (values, standard errors, correlations in fit.json)",
      "rms residual " + numberText(r.rms, 3) +
          (r.converged ? "" : " (NOT CONVERGED: " + r.note + ")"),
      "the original rig's comments are not kept"};
  if (!held.empty())
    header.insert(header.begin() + 2,
                  "not identifiable (their values here are what the fit ran "
                  "with, not estimates): " +
                      held);
  return rigYamlWithOverrides(text, opt.rig_path, withValues(opt, rep.free, r.used), header);
}

}  // namespace

FitReport runFit(const FitOptions& opt) {
  const std::string text = readRigFile(opt.rig_path);
  const Rig rig = loadPhysicalRig(text, opt.rig_path, opt.sets);
  requireDerivatives(rig, opt.rig_path, "fit");
  checkSensibleRanges(text, opt.rig_path, opt.sets, opt.strict);
  const MeasuredData data = loadData(opt.data_path, rig);
  const Engine& engine = chooseEngine("", opt.model, rig, opt.rig_path);
  if (opt.noise && !(*opt.noise > 0)) throw UsageError("--noise must be > 0");
  if (opt.starts < 1) throw UsageError("--starts must be at least 1");
  ceresPlugin();  // Ceres loaded now: a missing plugin is said before anything is written
  FitReport rep{opt.rig_path, opt.data_path, opt.model, {}, {}, {}, {}};
  rep.free = freeParameters(opt, text, rig, data, rep.start_from);
  FitProblem problem;
  problem.free = rep.free;
  problem.data = &data;
  problem.engine = &engine;
  problem.rig = [&](const std::vector<double>& v) {
    return loadRigText(text, opt.rig_path, withValues(opt, rep.free, v));
  };
  problem.settings.model = opt.model;
  problem.settings.noise = opt.noise;
  problem.settings.starts = opt.starts;
  problem.settings.local = opt.local;
  problem.settings.profile = opt.profile;
  try {
    rep.outcome = fitModel(problem);
  } catch (const std::invalid_argument& e) {
    throw UsageError(opt.data_path + ": " + e.what());
  }
  rep.fitted_rig_yaml = fittedRig(opt, text, rep);
  return rep;
}

namespace {

void printFit(const FitReport& rep, const OutputDir& dir, const std::vector<std::string>& files) {
  const FitOutcome& r = rep.outcome;
  const bool metres = r.quantity_names.size() == 1 && r.quantity_names[0] == "x";
  std::cout << "fit (" << rep.model << " model, " << r.observations.size() << " observations, "
            << r.evaluations << " model runs"
            << (r.jacobians > 0 ? ", " + std::to_string(r.jacobians) + " with derivatives" : "")
            << (r.converged ? "" : ", NOT CONVERGED") << "):\n";
  for (std::size_t j = 0; j < rep.free.size(); ++j) {
    std::cout << "  " << rep.free[j].name << " = ";
    if (r.values[j])
      std::cout << numberText(*r.values[j]) << " +- " << numberText(*r.std_errors[j], 2)
                << (r.std_error_from.size() > j && r.std_error_from[j] == "optima"
                        ? " (the spread of the optima found)"
                        : "");
    else
      std::cout << "not identifiable (" << r.not_identifiable_because[j] << "; kept at "
                << numberText(r.used[j]) << ")";
    std::cout << "   (start " << numberText(rep.free[j].start) << ", from " << rep.start_from[j]
              << ")\n";
  }
  std::cout << "  rms residual " << numberText(r.rms, 3) << (metres ? " m" : " rad") << "; "
            << r.note << "\n";
  if (r.optima.size() > 1) {
    std::cout << "  " << r.optima.size() << " distinct optima found (rms):";
    for (const Optimum& o : r.optima) std::cout << " " << numberText(o.rms, 3);
    std::cout << " (values in fit.json)\n";
  }
  std::cout << "files: " << dir.path() << "/ (";
  for (std::size_t k = 0; k < files.size(); ++k) std::cout << (k ? ", " : "") << files[k];
  std::cout << ")\n";
}

void writeFitFiles(const FitOptions& opt, const Rig& rig, const FitReport& rep) {
  OutputDir dir = [&] {
    try {
      OutputDir d(opt.out.empty() ? defaultOutputDir(rig.name, "fit") : opt.out);
      d.removeStaleOutputs();
      return d;
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("--out: ") + e.what());
    }
  }();
  writeFileAtomically(dir.file("fitted.yaml"), rep.fitted_rig_yaml);
  std::vector<std::string> files = {"fitted.yaml"};
  if (!opt.no_plot && plotFit(dir, "fit.png", rep,
                              rig.name + " - " + opt.model + " model fitted to " + opt.data_path))
    files.push_back("fit.png");
  files.push_back("fit.json");
  writeJsonFile(dir.file("fit.json"), fitJson(rep));
  if (!opt.quiet) printFit(rep, dir, files);
}

CLI::App* addFitOptions(CLI::App* cmd, FitOptions& opt) {
  cmd->add_option("RIG", opt.rig_path,
                  "rig file (physical units): what is known, and the "
                  "starting values of the free keys")
      ->required();
  cmd->add_option("DATA", opt.data_path,
                  "CSV with t (s) and any of theta_1..theta_N (rad), x (m); empty cells are "
                  "missing samples")
      ->required();
  cmd->add_option("--free", opt.free,
                  "a rig key to estimate (as --set names it), e.g. "
                  "metronomes.0.pendulum.decay_rate, platform.friction.mu, "
                  "metronomes.1.start.angle; metronomes.*.X: one value shared by every "
                  "metronome; repeatable")
      ->type_name("KEY")
      ->required()
      ->allow_extra_args(false);
  cmd->add_option("--set", opt.sets,
                  "override a rig key before fitting (a free key's start is used as given); "
                  "repeatable")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  cmd->add_option("--model", opt.model,
                  "full: the governing equations, every sample (default); slow: the slow flow "
                  "on the swings' amplitudes (faster, for long records)")
      ->check(CLI::IsMember({"full", "slow"}));
  addNumber(cmd, "--noise", opt.noise, kPositive,
            "the angles' measurement noise (rad; m when only x is fitted); default: "
            "estimated from the data's high-frequency part")
      ->type_name("SIGMA");
  addInteger(cmd, "--starts", opt.starts, 1, kMaxStarts,
             "try at most N starting points while no optimum is at the noise level "
             "(default 6)")
      ->type_name("N");
  cmd->add_flag("--local", opt.local,
                "only Levenberg-Marquardt on the whole record from each start (no envelopes, "
                "no growing windows): faster from a start close to the answer");
  cmd->add_flag("--profile", opt.profile,
                "profile every key (the others refitted at -+2 standard errors; always done "
                "with --model slow)");
  cmd->add_option("--out", opt.out, "output directory (default: runs/<rig name>-fit)")
      ->type_name("DIR");
  cmd->add_flag("-q,--quiet", opt.quiet, "no summary on stdout");
  cmd->add_flag("--no-plot", opt.no_plot, "write no fit.png");
  addStrictFlag(cmd, opt.strict);
  return cmd;
}

}  // namespace

CLI::App* addFitCommand(CLI::App& app, FitOptions& opt) {
  CLI::App* cmd = app.add_subcommand(
      "fit", "estimate rig keys from measured angles and platform positions (least squares)");
  addFitOptions(cmd, opt);
  cmd->footer(
      "Files in --out DIR: fitted.yaml (the rig with the fitted values, runnable as is), "
      "fit.json (values, std_errors, identifiable, correlation, rms, noise, converged and its "
      "note, every optimum found), fit.png.\n" +
      std::string(kFitExitCodes));
  return cmd;
}

int fitCommand(const FitOptions& opt) {
  FitReport rep;
  try {
    rep = runFit(opt);
  } catch (const ModelFailure& e) {
    std::cerr << "metrosync: error: the model fails at the starting values: " << e.what() << "\n";
    return kSimulationFailed;
  }
  for (const std::string& w : rep.outcome.warnings)
    std::cerr << "metrosync: warning: " << w << "\n";
  if (!rep.outcome.converged)
    std::cerr << "metrosync: warning: not converged: " << rep.outcome.note
              << "; see the residuals in fit.png\n";
  const Rig rig = loadRigText(readRigFile(opt.rig_path), opt.rig_path, opt.sets);
  writeFitFiles(opt, rig, rep);
  return kSuccess;
}

}  // namespace metrosync::cli
