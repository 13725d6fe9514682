#include "tools/cli/fit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "base/constants.h"
#include "base/number_text.h"
#include "models/scaling.h"
#include "sim/analysis/fit/ceres_plugin.h"
#include "sim/analysis/fit/data_file.h"
#include "sim/analysis/fit/least_squares.h"
#include "sim/analysis/fit/model_samples.h"
#include "sim/analysis/fit/section3.h"
#include "sim/analysis/fit/start_guess.h"
#include "sim/analysis/fit/swings.h"
#include "tools/cli/commands.h"
#include "tools/cli/engines.h"
#include "tools/cli/number_option.h"
#include "tools/cli/option_keys.h"
#include "tools/report/fit_files.h"
#include "yaml/rig_loader.h"
#include "yaml/rig_writer.h"

namespace metrosync::cli {

namespace {

// Model rows per small-angle period of metronome 1: the Hermite interpolant between rows is then
// ~1e-7 rad off at 45 degrees, four orders below a camera's noise.
constexpr double kRowsPerPeriod = 100.0;

const char* kFitExitCodes =
    "Exit codes: 0 fitted; 2 bad command line, rig or data file (nothing written); 3 the model "
    "fails at the starting values; 1 anything else.";

// A rig the commands can fit: loaded with the overrides, in physical units.
Rig loadPhysicalRig(const std::string& text, const std::string& name,
                    const std::vector<std::string>& sets) {
  Rig rig = loadRigText(text, name, sets);
  if (rig.units != Units::Physical)
    throw UsageError(name +
                     ": a scaled rig (units: scaled) has no seconds or radians to match "
                     "measured data; write the rig in physical units");
  return rig;
}

MeasuredData loadData(const std::string& path, const Rig& rig) {
  try {
    return readDataFile(path, static_cast<int>(rig.metronomes.size()));
  } catch (const DataError& e) {
    throw UsageError(e.what());
  }
}

// Keys that cannot be negative are bounded at 0; a start value of 0 gets a typical scale.
FreeParameter freeParameter(const RigKey& key, double start) {
  FreeParameter p;
  p.key = key.key.text();
  p.start = start;
  const std::string& last = key.key.leaf();
  const std::string parent = key.key.parent();
  for (const char* k : {"damping", "decay_rate", "mu", "c", "impulse", "k", "inertia", "mass",
                        "box_mass", "steady_amplitude"})
    if (last == k) p.lower = 0.0;
  if (last == "angle" && parent == "escapement") p.lower = 0.0;
  double typical = 1.0;  // rad/s, and anything else
  if (parent == "start")
    typical = (last == "angle") ? 0.1 : (last == "x" || last == "v") ? 0.01 : 1.0;
  p.scale = start != 0.0 ? std::abs(start) : typical;
  return p;
}

// The --free keys resolved against the rig (docs/keys.md): a bad key is refused as any option's
// is, two keys setting one rig key too. A key with '*' reaches fit as a group of paths (its
// `paths`) that would move as one shared value; fit does not fit shared values yet.
std::vector<RigKey> freeKeys(const std::string& text, const FitOptions& opt) {
  std::vector<OptionKey> keys;
  for (const std::string& k : opt.free)
    keys.push_back(resolveOptionKey({text, opt.rig_path, opt.sets}, "--free", k, false));
  refuseSharedKeys(keys);
  std::vector<RigKey> out;
  for (const OptionKey& k : keys) {
    if (k.key.group() && k.key.paths.size() > 1)
      throw UsageError(k.typed + ": the key stands for " + std::to_string(k.key.paths.size()) +
                       " rig keys (" + k.key.paths.front().text() + " ... " +
                       k.key.paths.back().text() +
                       "), to be fitted as one shared value, which fit cannot do yet: free "
                       "each of them, e.g. --free " +
                       k.key.paths.front().text());
    out.push_back(k.key);
  }
  return out;
}

// The starting value of `key` (one path): a section-3 shortcut where one applies, else the rig's
// value (0 for an absent start key). Checks that the key can be set to a number in this rig.
FreeParameter startOf(const RigKey& key, const std::string& text, const FitOptions& opt,
                      const Rig& rig, const MeasuredData& data, std::string& from) {
  const std::string& path = key.paths.front().text();  // names and indices only
  std::optional<double> v = rigNumber(text, opt.rig_path, opt.sets, path);
  from = "rig";
  if (!v) {
    if (key.key.parent() != "start")
      throw UsageError("--free " + key.key.text() + ": the rig gives no value for it (free the " +
                       "key the rig gives: damping or decay_rate, impulse or steady_amplitude, " +
                       "as written in " + opt.rig_path + ")");
    v = 0.0;
    from = "default";
  }
  if (const std::optional<StartGuess> g = section3Guess(path, rig, data)) {
    v = g->value;
    from = g->from;
  }
  std::vector<std::string> sets = opt.sets;
  sets.push_back(path + "=" + exactNumberText(*v));
  loadRigText(text, opt.rig_path, sets);  // the key takes this value
  return freeParameter(key, *v);
}

double medianSpacing(const std::vector<double>& t) {
  std::vector<double> d;
  for (std::size_t i = 1; i < t.size(); ++i) d.push_back(t[i] - t[i - 1]);
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

// The model's row interval: a whole fraction of the data's spacing (so that rows fall on the
// samples of a steady camera) no longer than a period / kRowsPerPeriod.
double rowInterval(const MeasuredData& data, const Rig& rig) {
  const double period = 2 * kPi * computeScaled(rig).time_scale_s;
  const double dt = medianSpacing(data.t_s), longest = period / kRowsPerPeriod;
  return dt / std::ceil(dt / longest);
}

// The observations: every sample at t >= 0 (full model), or the swings' amplitudes of every
// theta column (slow flow; x is not a slow-flow quantity and is left out).
void addObservations(const MeasuredData& data, bool slow, FitSetup& s,
                     std::vector<SampleRequest>& requests) {
  std::vector<int> metronome;  // of each quantity, -1 for x
  bool any_angle = false;
  for (const DataColumn& c : data.columns) any_angle = any_angle || c.metronome >= 0;
  for (const DataColumn& c : data.columns) {
    if (slow && c.metronome < 0) {
      std::cerr << "metrosync: warning: --model slow: column " << c.name << " is not used\n";
      continue;
    }
    const int q = static_cast<int>(s.quantity_names.size());
    const int group = (c.metronome < 0 && any_angle) ? 1 : 0;
    s.quantity_names.push_back(c.name);
    metronome.push_back(c.metronome);
    if (slow) {
      for (const Swing& w : findSwings(data.t_s, c.values, SwingWindow::Peak).swings)
        s.observations.push_back({w.t_s, q, group, w.amplitude});
    } else {
      for (std::size_t i = 0; i < data.t_s.size(); ++i)
        if (data.t_s[i] >= 0 && !std::isnan(c.values[i]))
          s.observations.push_back({data.t_s[i], q, group, c.values[i]});
    }
  }
  for (const Observation& o : s.observations) requests.push_back({o.t_s, metronome[o.quantity]});
  if (s.observations.empty()) throw UsageError(data.path + ": no sample to fit");
}

std::vector<std::string> fittedSets(const FitOptions& opt, const FitSetup& s, const FitResult& r) {
  std::vector<std::string> sets = opt.sets;
  for (std::size_t j = 0; j < s.free.size(); ++j)
    if (r.values[j]) sets.push_back(s.free[j].key + "=" + exactNumberText(*r.values[j]));
  return sets;
}

void printFit(const FitSetup& s, const FitResult& r, const FitContext& ctx, const OutputDir& dir,
              const std::vector<std::string>& files) {
  std::cout << "fit (" << ctx.model << " model, " << s.observations.size() << " observations, "
            << r.evaluations << " model runs" << (r.converged ? "" : ", not converged") << "):\n";
  for (std::size_t j = 0; j < s.free.size(); ++j) {
    std::cout << "  " << s.free[j].key << " = ";
    if (r.values[j])
      std::cout << numberText(*r.values[j]) << " +- " << numberText(*r.std_errors[j], 2);
    else
      std::cout << "not identifiable from these data (kept at " << numberText(r.used[j]) << ")";
    std::cout << "   (start " << numberText(ctx.starts[j]) << ", from " << ctx.start_from[j]
              << ")\n";
  }
  std::cout << "  rms residual " << numberText(r.rms, 3)
            << (s.quantity_names.size() == 1 && s.quantity_names[0] == "x" ? " m" : " rad")
            << "\nfiles: " << dir.path() << "/ (";
  for (std::size_t k = 0; k < files.size(); ++k) std::cout << (k ? ", " : "") << files[k];
  std::cout << ")\n";
}

void writeFitFiles(const FitOptions& opt, const std::string& text, const Rig& rig,
                   const FitSetup& s, const FitResult& r, const FitContext& ctx) {
  OutputDir dir = [&] {
    try {
      OutputDir d(opt.out.empty() ? defaultOutputDir(rig.name, "fit") : opt.out);
      d.removeStaleOutputs();
      return d;
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("--out: ") + e.what());
    }
  }();
  std::string keys;
  for (const FreeParameter& p : s.free) keys += (keys.empty() ? "" : ", ") + p.key;
  const std::vector<std::string> header = {
      "Fitted by metrosync " + std::string(metrosyncVersion()) + " fit: rig " + opt.rig_path +
          ", data " + opt.data_path + ", " + ctx.model + " model",
      "free: " + keys + " (values, standard errors, correlations in fit.json)",
      "rms residual " + numberText(r.rms, 3) + "; the original rig's comments are not kept"};
  writeFileAtomically(dir.file("fitted.yaml"),
                      rigYamlWithOverrides(text, opt.rig_path, fittedSets(opt, s, r), header));
  std::vector<std::string> files = {"fitted.yaml"};
  if (!opt.no_plot && plotFit(dir, "fit.png", s, r,
                              rig.name + " - " + ctx.model + " model fitted to " + opt.data_path))
    files.push_back("fit.png");
  files.push_back("fit.json");
  writeFileAtomically(dir.file("fit.json"), fitJson(s, r, ctx).dump(2) + "\n");
  if (!opt.quiet) printFit(s, r, ctx, dir, files);
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
                  "metronomes.1.start.angle; repeatable")
      ->type_name("KEY")
      ->required()
      ->allow_extra_args(false);
  cmd->add_option("--set", opt.sets, "override a rig key before fitting; repeatable")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  cmd->add_option("--model", opt.model,
                  "full: the governing equations, every sample (default); slow: the slow flow "
                  "on the swings' amplitudes (faster, for long records)")
      ->check(CLI::IsMember({"full", "slow"}));
  cmd->add_option("--out", opt.out, "output directory (default: runs/<rig name>-fit)")
      ->type_name("DIR");
  cmd->add_flag("-q,--quiet", opt.quiet, "no summary on stdout");
  cmd->add_flag("--no-plot", opt.no_plot, "write no fit.png");
  return cmd;
}

}  // namespace

CLI::App* addFitCommand(CLI::App& app, FitOptions& opt) {
  CLI::App* cmd = app.add_subcommand(
      "fit", "estimate rig keys from measured angles and platform positions (least squares)");
  addFitOptions(cmd, opt);
  cmd->footer(
      "Files in --out DIR: fitted.yaml (the rig with the fitted values, runnable as is), "
      "fit.json (values, std_errors, identifiable, correlation, rms, evaluations), fit.png.\n" +
      std::string(kFitExitCodes));
  return cmd;
}

int fitCommand(const FitOptions& opt) {
  const std::string text = readRigFile(opt.rig_path);
  const Rig rig = loadPhysicalRig(text, opt.rig_path, opt.sets);
  const std::vector<RigKey> keys = freeKeys(text, opt);
  const MeasuredData data = loadData(opt.data_path, rig);
  const Engine& engine = chooseEngine("", opt.model, rig, opt.rig_path);
  ceresPlugin();  // Ceres loaded now: a missing plugin is said before anything is written
  FitSetup setup;
  FitContext ctx{opt.rig_path, opt.data_path, opt.model, {}, {}};
  for (const RigKey& key : keys) {
    std::string from;
    setup.free.push_back(startOf(key, text, opt, rig, data, from));
    ctx.starts.push_back(setup.free.back().start);
    ctx.start_from.push_back(from);
  }
  std::vector<SampleRequest> requests;
  addObservations(data, opt.model == "slow", setup, requests);
  const double row_dt = rowInterval(data, rig);
  setup.predict = [&](const std::vector<double>& v) {
    std::vector<std::string> sets = opt.sets;
    for (std::size_t j = 0; j < v.size(); ++j)
      sets.push_back(setup.free[j].key + "=" + exactNumberText(v[j]));
    return sampleModel(engine, loadRigText(text, opt.rig_path, sets), requests, row_dt);
  };
  try {  // the model must run at the start: else exit 3, nothing written
    setup.predict(ctx.starts);
  } catch (const ModelFailure& e) {
    std::cerr << "metrosync: error: the model fails at the starting values: " << e.what() << "\n";
    return kSimulationFailed;
  }
  FitResult result;
  try {
    result = fitLeastSquares(setup);
  } catch (const std::invalid_argument& e) {
    throw UsageError(opt.data_path + ": " + e.what());
  }
  if (!result.converged)
    std::cerr << "metrosync: warning: the fit did not converge (" << result.solver_summary
              << "): check the rig, the starting values and the residuals in fit.png\n";
  writeFitFiles(opt, text, rig, setup, result, ctx);
  return kSuccess;
}

namespace {

nlohmann::json estimateJson(const Estimate& e) {
  return {{"value", numberOrNull(e.value)}, {"std_error", numberOrNull(e.std_error)}};
}

const DataColumn& columnOf(const MeasuredData& data, const std::string& name) {
  const DataColumn* c = data.find(name);
  if (!c) throw UsageError(data.path + ": no column " + name);
  return *c;
}

// The closed forms' own complaints (too few swings) are about the data file.
template <class F>
auto measured(const std::string& path, F&& f) {
  try {
    return f();
  } catch (const std::invalid_argument& e) {
    throw UsageError(path + ": " + e.what());
  }
}

std::string keyOf(int i, const std::string& rest) {
  return "metronomes." + std::to_string(i) + "." + rest;
}

}  // namespace

CLI::App* addMeasureCommand(CLI::App& app, MeasureOptions& opt) {
  CLI::App* cmd = app.add_subcommand(
      "measure",
      "the paper's section-3 closed forms: damping from a free decay, mu-bar from a "
      "linear decay, the impulse from a steady amplitude");
  cmd->add_option("RIG", opt.rig_path,
                  "rig file (physical units) with the masses, lengths and theta_c; default: the "
                  "built-in rig");
  cmd->add_option("--set", opt.sets, "override a rig key; repeatable")->type_name("KEY=VALUE");
  cmd->add_option("--decay", opt.decay,
                  "CSV (t, theta_I): one pendulum swinging below theta_c on a still table")
      ->type_name("FILE");
  cmd->add_option("--friction", opt.friction,
                  "CSV (t, x): the board on springs, the metronomes locked (section 3A)")
      ->type_name("FILE");
  cmd->add_option("--steady", opt.steady,
                  "CSV (t, theta_I): one metronome ticking at its steady amplitude on a still "
                  "table")
      ->type_name("FILE");
  addInteger(cmd, "--metronome", opt.metronome, 1, kMaxMetronomes,
             "which metronome's theta_I the --decay and --steady files hold (default 1)")
      ->type_name("I");
  cmd->add_option("--out", opt.out, "output directory (default: runs/<rig name>-measure)")
      ->type_name("DIR");
  cmd->add_flag("-q,--quiet", opt.quiet, "no JSON on stdout");
  cmd->footer(
      "Writes DIR/measure.json (each estimate with its standard error, and the --set lines that "
      "put them in the rig) and prints it. Exit codes: 0 measured; 2 bad command line, rig or data "
      "(too few swings included); 1 anything else.");
  return cmd;
}

namespace {

// What the three experiments add to measure.json: each its own object and a --set line.
struct Measurements {
  nlohmann::json json;
  nlohmann::json sets = nlohmann::json::array();
  Estimate damping;  // metronome I's nu-bar: the free decay's, else the rig's
  std::string damping_from = "rig";
};

void measureDecay(const MeasureOptions& opt, const Rig& rig, int i, Measurements& m) {
  const std::string theta = "theta_" + std::to_string(i + 1);
  const MeasuredData d = loadData(opt.decay, rig);
  const FreeDecay f =
      measured(opt.decay, [&] { return measureFreeDecay(d.t_s, columnOf(d, theta).values); });
  m.damping = dampingFromDecayRate(rig, i, f.rate_per_s);
  m.damping_from = "free decay";
  const bool below = f.largest_amplitude < rig.metronomes[i].theta_c_rad;
  if (!below)
    std::cerr << "metrosync: warning: " << opt.decay << ": the largest swing, "
              << numberText(f.largest_amplitude, 3)
              << " rad, reaches theta_c: the escapement ticks, the decay is not free\n";
  m.json["free_decay"] = {{"file", opt.decay},
                          {"column", theta},
                          {"swings", f.swings},
                          {"period_s", estimateJson(f.period_s)},
                          {"decay_rate_per_s", estimateJson(f.rate_per_s)},
                          {"damping_kg_s", estimateJson(m.damping)},
                          {"nu", estimateJson(scaledNuFromDecayRate(rig, i, f.rate_per_s))},
                          {"largest_amplitude_rad", f.largest_amplitude},
                          {"below_theta_c", below}};
  m.sets.push_back(keyOf(i, "pendulum.decay_rate=") + exactNumberText(f.rate_per_s.value));
}

void measureFriction(const MeasureOptions& opt, const Rig& rig, Measurements& m) {
  const MeasuredData d = loadData(opt.friction, rig);
  const LinearDecay l = measured(opt.friction, [&] {
    return measureLinearDecay(d.t_s, columnOf(d, "x").values, rig.gravity_m_s2);
  });
  const double eps = computeScaled(rig).epsilon, k = 1.0 / (eps * std::sqrt(eps));
  m.json["linear_decay"] = {{"file", opt.friction},
                            {"column", "x"},
                            {"swings", l.swings},
                            {"period_s", estimateJson(l.period_s)},
                            {"slope_m_per_s", estimateJson(l.slope_m_per_s)},
                            {"mu_bar", estimateJson(l.mu_bar)},
                            {"mu", estimateJson({k * l.mu_bar.value, k * l.mu_bar.std_error})}};
  m.sets.push_back("platform.friction.mu=" + exactNumberText(l.mu_bar.value));
}

void measureSteady(const MeasureOptions& opt, const Rig& rig, int i, Measurements& m) {
  const std::string theta = "theta_" + std::to_string(i + 1);
  const MeasuredData d = loadData(opt.steady, rig);
  const SteadyAmplitude a = measured(
      opt.steady, [&] { return measureSteadyAmplitude(d.t_s, columnOf(d, theta).values); });
  const Impulse J = measured(
      opt.steady, [&] { return impulseFromSteadyAmplitude(rig, i, a.amplitude_rad, m.damping); });
  m.json["steady_amplitude"] = {{"file", opt.steady},
                                {"column", theta},
                                {"swings", a.swings},
                                {"amplitude_rad", estimateJson(a.amplitude_rad)},
                                {"J", estimateJson(J.scaled)},
                                {"impulse_Nms", estimateJson(J.impulse_Nms)},
                                {"damping_from", m.damping_from}};
  m.sets.push_back(keyOf(i, "escapement.impulse=") + exactNumberText(J.impulse_Nms.value));
}

}  // namespace

int measureCommand(const MeasureOptions& opt) {
  if (opt.decay.empty() && opt.friction.empty() && opt.steady.empty())
    throw UsageError("measure: give at least one of --decay, --friction, --steady");
  const std::string name = opt.rig_path.empty() ? "<default rig>" : opt.rig_path;
  const std::string text = opt.rig_path.empty() ? defaultRigYaml() : readRigFile(opt.rig_path);
  const Rig rig = loadPhysicalRig(text, name, opt.sets);
  const int i = opt.metronome - 1;
  if (i >= static_cast<int>(rig.metronomes.size()))
    throw UsageError("--metronome " + std::to_string(opt.metronome) + ": the rig has " +
                     std::to_string(rig.metronomes.size()) + " metronomes");
  Measurements m;
  m.json = {{"rig", name}, {"metronome", opt.metronome}};
  m.damping = {rig.metronomes[i].damping_kg_s, 0.0};
  if (!opt.decay.empty()) measureDecay(opt, rig, i, m);
  if (!opt.friction.empty()) measureFriction(opt, rig, m);
  if (!opt.steady.empty()) measureSteady(opt, rig, i, m);
  m.json["set"] = m.sets;
  OutputDir dir = [&] {
    try {
      return OutputDir(opt.out.empty() ? defaultOutputDir(rig.name, "measure") : opt.out);
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("--out: ") + e.what());
    }
  }();
  writeFileAtomically(dir.file("measure.json"), m.json.dump(2) + "\n");
  if (!opt.quiet) std::cout << m.json.dump(2) << "\n";
  return kSuccess;
}

}  // namespace metrosync::cli
