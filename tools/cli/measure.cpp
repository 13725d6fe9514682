#include <cmath>
#include <cstdio>
#include <iostream>

#include "base/number_text.h"
#include "models/scaling.h"
#include "sim/analysis/fit/section3.h"
#include "tools/cli/commands.h"
#include "tools/cli/fit.h"
#include "tools/cli/fit_inputs.h"
#include "tools/cli/number_option.h"
#include "tools/cli/range_warnings.h"
#include "tools/report/json_file.h"
#include "yaml/rig_limits.h"
#include "yaml/rig_loader.h"
#include "yaml/rig_writer.h"

namespace metrosync::cli {

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

// The rig measure reads, and which of two equivalent keys it gives, so that the `set` lines
// apply to it as they are (a rig gives damping or decay_rate, impulse or steady_amplitude, and a
// network of one names its platform platforms.0).
struct RigText {
  std::string text, name;
  std::vector<std::string> sets;
  bool gives(const std::string& key) const { return rigNumber(text, name, sets, key).has_value(); }
  // "platform" or "platforms.0"
  std::string platform() const { return gives("platform.mass") ? "platform" : "platforms.0"; }
  // metronome i's key prefix: "metronomes.I" or "platforms.0.metronomes.I"
  std::string metronome(int i) const {
    const std::string own = "metronomes." + std::to_string(i);
    return gives(own + ".pendulum.mass") ? own : "platforms.0." + own;
  }
};

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
  addStrictFlag(cmd, opt.strict);
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

void measureDecay(const MeasureOptions& opt, const RigText& rt, const Rig& rig, int i,
                  Measurements& m) {
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
  const std::string pendulum = rt.metronome(i) + ".pendulum";
  m.sets.push_back(rt.gives(pendulum + ".damping")
                       ? pendulum + ".damping=" + exactNumberText(m.damping.value)
                       : pendulum + ".decay_rate=" + exactNumberText(f.rate_per_s.value));
}

void measureFriction(const MeasureOptions& opt, const RigText& rt, const Rig& rig,
                     Measurements& m) {
  const MeasuredData d = loadData(opt.friction, rig);
  const BoardDecay l = measured(opt.friction, [&] {
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
  // the measured friction is Coulomb's: a rig of another law gets the law with it
  const std::string friction = rt.platform() + ".friction";
  const std::string mu = exactNumberText(l.mu_bar.value);
  m.sets.push_back(rt.gives(friction + ".mu") ? friction + ".mu=" + mu
                                              : friction + "={law: coulomb, mu: " + mu + "}");
}

void measureSteady(const MeasureOptions& opt, const RigText& rt, const Rig& rig, int i,
                   Measurements& m) {
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
  // a rig that gives steady_amplitude gets the measured amplitude (it makes the same impulse with
  // the damping measured or given), else the impulse
  const std::string esc = rt.metronome(i) + ".escapement";
  m.sets.push_back(rt.gives(esc + ".steady_amplitude")
                       ? esc + ".steady_amplitude=" + exactNumberText(a.amplitude_rad.value)
                       : esc + ".impulse=" + exactNumberText(J.impulse_Nms.value));
}

}  // namespace

int measureCommand(const MeasureOptions& opt) {
  if (opt.decay.empty() && opt.friction.empty() && opt.steady.empty())
    throw UsageError("measure: give at least one of --decay, --friction, --steady");
  const std::string name = opt.rig_path.empty() ? "<default rig>" : opt.rig_path;
  const std::string text = opt.rig_path.empty() ? defaultRigYaml() : readRigFile(opt.rig_path);
  const Rig rig = loadPhysicalRig(text, name, opt.sets);
  checkSensibleRanges(text, name, opt.sets, opt.strict);
  const int i = opt.metronome - 1;
  if (i >= static_cast<int>(rig.metronomes.size()))
    throw UsageError("--metronome " + std::to_string(opt.metronome) + ": the rig has " +
                     std::to_string(rig.metronomes.size()) + " metronomes");
  Measurements m;
  m.json = {{"rig", name}, {"metronome", opt.metronome}};
  m.damping = {rig.metronomes[i].damping_kg_s, 0.0};
  const RigText rt{text, name, opt.sets};
  if (!opt.decay.empty()) measureDecay(opt, rt, rig, i, m);
  if (!opt.friction.empty()) measureFriction(opt, rt, rig, m);
  if (!opt.steady.empty()) measureSteady(opt, rt, rig, i, m);
  m.json["set"] = m.sets;
  OutputDir dir = [&] {
    try {
      return OutputDir(opt.out.empty() ? defaultOutputDir(rig.name, "measure") : opt.out);
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("--out: ") + e.what());
    }
  }();
  writeJsonFile(dir.file("measure.json"), m.json);
  if (!opt.quiet) std::cout << m.json.dump(2) << "\n";
  return kSuccess;
}

}  // namespace metrosync::cli
