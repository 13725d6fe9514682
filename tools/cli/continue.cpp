#include "tools/cli/continue.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "base/constants.h"
#include "base/number_text.h"
#include "models/scaling.h"
#include "models/slow_flow.h"
#include "sim/analysis/continuation/merge.h"
#include "sim/analysis/continuation/slow_flow_continuation.h"
#include "sim/analysis/continuation/start_states.h"
#include "tools/cli/commands.h"
#include "tools/cli/continue_full.h"
#include "tools/cli/engines.h"
#include "tools/cli/number_option.h"
#include "tools/cli/option_keys.h"
#include "tools/cli/range_warnings.h"
#include "tools/report/continuation_report.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

namespace {
// --max-points: a branch point is a Newton solve of 2N - 1 unknowns and one CSV row; 10^6 points
// per direction bound a continuation to minutes and its branches.csv to ~100 MB per branch.
constexpr long long kMaxContinuationPoints = 1000000;
}  // namespace

namespace {

using namespace metrosync::continuation;
using Cd = std::complex<double>;

ContinueOptions& options() {
  static ContinueOptions opt;
  return opt;
}

std::string rigDisplay(const ContinueOptions& opt) {
  return opt.rig_path.empty() ? "<default rig>" : opt.rig_path;
}

std::string rigText(const ContinueOptions& opt) {
  if (opt.rig_path.empty()) return defaultRigYaml();
  std::ifstream in(opt.rig_path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw RigError(opt.rig_path + ": cannot read the rig file");
  return text.str();
}

// The slow flow's inputs: equal when KEY has no effect on it (the law compared as a value: every
// parameter of it counts).
bool sameSlowFlow(const ScaledParams& a, const ScaledParams& b) {
  return a.friction == b.friction && a.nu == b.nu && a.J == b.J && a.theta_c == b.theta_c &&
         a.alpha == b.alpha && a.locked == b.locked;
}

// The rig with KEY_k = p_k, scaled; values the rig refuses give NaN parameters, so the corrector
// fails there and the step control stays out.
ScaledParams scaledAt(const ContinueOptions& opt, const std::vector<std::string>& keys,
                      const std::vector<double>& values) {
  std::vector<std::string> o;
  for (size_t k = 0; k < keys.size(); ++k) o.push_back(keys[k] + "=" + roundTripText(values[k]));
  try {
    return computeScaled(loadContinueRig(opt, o));
  } catch (const std::exception&) {
    ScaledParams bad = computeScaled(loadContinueRig(opt, {}));
    for (double& v : bad.nu) v = std::nan("");
    return bad;
  }
}

ParamsAt paramsAt(const ContinueOptions& opt) {
  return [opt](double p) { return scaledAt(opt, {opt.param}, {p}); };
}

ParamsAt2 paramsAt2(const ContinueOptions& opt) {
  return [opt](double p1, double p2) { return scaledAt(opt, {opt.param, opt.fold_key}, {p1, p2}); };
}

// The scaled parameters with KEY = value; a value that makes one of them infinite or NaN (e.g.
// --to 1e308) is refused naming `which` option gave it. A value the loader refuses (mu < 0) is said
// in the loader's words (--param KEY=VALUE: ...).
ScaledParams finiteScaledAt(const ContinueOptions& opt, double value, const std::string& which) {
  const ScaledParams p =
      computeScaled(loadContinueRig(opt, {opt.param + "=" + roundTripText(value)}));
  const std::pair<const char*, const std::vector<double>*> lists[] = {
      {"nu", &p.nu}, {"J", &p.J}, {"theta_c", &p.theta_c}, {"alpha", &p.alpha}, {"zeta", &p.zeta}};
  std::string bad;
  const std::vector<LawParameter>& law_keys = p.friction.kind().parameters();
  for (std::size_t k = 0; k < law_keys.size(); ++k)
    if (!std::isfinite(p.friction.values()[k])) bad = law_keys[k].key;
  for (const auto& [name, v] : lists)
    for (double x : *v)
      if (!std::isfinite(x)) bad = name;
  if (!bad.empty())
    throw UsageError(which + ": " + opt.param + " = " + roundTripText(value) +
                     " makes the scaled " + bad +
                     " infinite or undefined; choose a value nearer the rig's");
  return p;
}

// The slow flow at values inside the range, sampled: a range beyond the numbers (--to 1e308)
// makes its parameters infinite on the way although both ends are finite. Such a range is bad
// input (exit 2), not a branch whose corrector fails at the first step.
void checkRangeInside(const ContinueOptions& opt, double from, const std::string& option) {
  constexpr int kRangeSamples = 8;  // the continuation's steps are ~1/100 of the range
  for (int k = 1; k < kRangeSamples; ++k) {
    const double v = from + (opt.to - from) * k / kRangeSamples;
    try {
      SlowFlow flow(scaledAt(opt, {opt.param}, {v}));
    } catch (const std::invalid_argument& e) {
      throw UsageError(option + " " + opt.param + " from " + roundTripText(from) + " to " +
                       roundTripText(opt.to) + ": " + e.what() +
                       " on the way (the range leaves the range of the " +
                       "numbers); choose a --to nearer the start");
    }
  }
}

// The start value of opt.param, typed after `option` (--param, or --fold for KEY2).
double startValue(const ContinueOptions& opt, const std::string& option = "--param") {
  const Rig rig = loadContinueRig(opt, {});  // the rig itself must load
  const std::string display = rigDisplay(opt);
  const std::string text = rigText(opt);
  const RigKey key = resolveOptionKey({text, display, opt.sets}, option, opt.param, false).key;
  if (key.key.text() == "epsilon")
    throw UsageError(option +
                     " epsilon: epsilon has no effect on the slow flow (it only sets the "
                     "time scale of the full model); choose a key the slow flow depends on");
  // a key with '*': the rig's value at its first element (metronome 1 for metronomes.*.X)
  const std::optional<double> in_rig = rigNumber(text, display, opt.sets, key.paths[0].text());
  if (!opt.from && !in_rig)
    throw UsageError(option + " " + opt.param +
                     ": the key is not set in the rig (its default applies); give --from VALUE");
  const double from = opt.from ? *opt.from : *in_rig;  // both finite (tools/cli/number_option.h)
  if (opt.to == from)
    throw UsageError("--to " + roundTripText(opt.to) + ": must differ from the start value " +
                     opt.param + " = " + roundTripText(from));
  const ScaledParams a = finiteScaledAt(opt, from, opt.from ? "--from" : "the rig's value");
  const ScaledParams b = finiteScaledAt(opt, opt.to, "--to");
  if (sameSlowFlow(a, b))
    throw UsageError(option + " " + opt.param + ": has no effect on the slow flow (its scaled " +
                     "parameters are the same at " + roundTripText(from) + " and " +
                     roundTripText(opt.to) + ")");
  checkRangeInside(opt, from, option);
  return from;
}

std::vector<double> parseList(const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    size_t used = 0;
    double x = 0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || item.find_first_not_of(" \t", used) != std::string::npos)
      throw UsageError("--start " + text + ": '" + item + "' is not a number");
    v.push_back(x);
  }
  return v;
}

// The start state (rotated z, N x 1) and how it was found.
std::vector<Cd> startState(const ContinueOptions& opt, const ScaledParams& sp, std::string& how) {
  const int n = static_cast<int>(sp.nu.size());
  if (!opt.start.empty()) {
    const std::vector<double> v = parseList(opt.start);
    if (static_cast<int>(v.size()) != 2 * n - 1)
      throw UsageError("--start " + opt.start + ": expected " + std::to_string(2 * n - 1) +
                       " numbers A_1..A_" + std::to_string(n) + ",psi_2..psi_" + std::to_string(n));
    for (int i = 0; i < n; ++i)
      if (!(v[i] >= 0)) throw UsageError("--start: A_" + std::to_string(i + 1) + " must be >= 0");
    how = "--start " + opt.start;
    return stateFrom({v.begin(), v.begin() + n}, {v.begin() + n, v.end()});
  }
  const SettledState st = settleFromStart(sp, sp.tau_end > 0 ? sp.tau_end : 300.0);
  if (!st.settled)
    throw UsageError("the rig's start does not settle to a locked state (slow flow up to tau = " +
                     roundTripText(st.tau) + "): " + st.why + "; give --start A_1,..,psi_N");
  how = "the rig's start, settled by the slow flow at tau = " + roundTripText(st.tau);
  return st.z;
}

ContinuationSettings settingsFor(const ContinueOptions& opt, double from) {
  // --step and --max-points are checked when parsed (tools/cli/number_option.h); a step of 0 is
  // the option left out
  ContinuationSettings s;
  s.p_min = std::min(from, opt.to);
  s.p_max = std::max(from, opt.to);
  // the arclength in units of the range: a step of h moves the parameter by up to h of its range
  // or the state by up to h, whatever the size of the key (a physical mu of 1e-3 or a scaled 0.4)
  s.p_scale = s.p_max - s.p_min;
  constexpr double kFirstStep = 0.01, kMaxStep = 0.05;
  // kMaxStep is the cap for a pair; when every metronome moves alike, the state's arclength grows
  // as the square root of their number, so the cap does too: each amplitude moves as far per
  // step as in a pair (32 metronomes: 4 times the pair's cap, not 500 points along a range)
  const double metronomes = static_cast<double>(loadContinueRig(opt, {}).metronomes.size());
  const double cap = kMaxStep * std::sqrt(std::max(1.0, metronomes / 2));
  s.step = opt.step > 0 ? opt.step / s.p_scale : kFirstStep;
  s.step_max = std::max(s.step, cap);
  s.max_points = opt.max_points;
  return s;
}

// KEY2's start (the rig's value), checked like KEY's.
double secondStart(const ContinueOptions& opt) {
  const std::string display = rigDisplay(opt);
  const std::string text = rigText(opt);
  const KeyedRig rig{text, display, opt.sets};
  refuseSharedKeys({resolveOptionKey(rig, "--param", opt.param, false),
                    resolveOptionKey(rig, "--fold", opt.fold_key, false)});
  ContinueOptions second = opt;
  second.param = opt.fold_key, second.to = opt.to2, second.from.reset();
  return startValue(second, "--fold");
}

std::string outDir(const ContinueOptions& opt, const Rig& rig) {
  return opt.out.empty() ? "runs/" + rig.name + "-continue" : opt.out;
}

// KEY2's settings for the curves: its range, in units of its span.
ContinuationSettings curveSettings(double from2, double to2) {
  ContinuationSettings s;
  s.p_min = std::min(from2, to2), s.p_max = std::max(from2, to2);
  s.p_scale = s.p_max - s.p_min;
  // the curve's arclength is mostly in KEY and the state (O(1)), not only KEY2's span
  constexpr double kCurveStep = 0.01, kCurveStepMax = 0.05;
  s.step = kCurveStep, s.step_max = kCurveStepMax;
  return s;
}

// The continuation's inputs from the options (the rig loaded with KEY = from).
SlowFlowContinuationSpec slowFlowSpec(const ContinueOptions& opt, double from, std::string& how) {
  const ScaledParams sp =
      computeScaled(loadContinueRig(opt, {opt.param + "=" + roundTripText(from)}));
  SlowFlowContinuationSpec spec;
  spec.params = paramsAt(opt);
  spec.from = from, spec.to = opt.to;
  spec.settings = settingsFor(opt, from);
  if (!opt.all) spec.start = startState(opt, sp, how);
  spec.cycles = !opt.no_cycles;
  spec.cycle_points = opt.cycle_points;
  if (!opt.fold_key.empty()) {
    spec.params2 = paramsAt2(opt);
    spec.from2 = secondStart(opt), spec.to2 = opt.to2;
    spec.settings2 = curveSettings(spec.from2, spec.to2);
  }
  return spec;
}

void printBranchEnds(const ContinuationResult& r) {
  for (const auto& b : r.branches) {
    std::cout << "  branch " << b.id << " (" << b.points << " points"
              << (b.neutral ? ", a neutral family" : "") << "): " << b.end_backward << " | "
              << b.end_forward << "\n";
    if (b.max_points)
      std::cout << "    stopped by --max-points: raise it to follow the branch further\n";
  }
}

void printCycles(const ContinuationResult& r, int budget) {
  for (const auto& c : r.cycles) {
    std::cout << "  cycle " << c.id << " from the Hopf point at " << r.param << " = "
              << roundTripText(c.hopf_value) << ": " << c.points.size() << " points (budget "
              << budget << ", --cycle-points), " << c.end << "\n";
    for (const auto& f : c.folds)
      std::cout << "    fold of cycles at " << r.param << " = " << roundTripText(f.at.value)
                << " (period " << roundTripText(f.at.period) << "): " << f.check << "\n";
    for (const auto& w : c.changes) std::cout << "    " << w << "\n";
  }
}

void printSummary(const ContinuationResult& r, const std::string& dir, int cycle_budget) {
  std::cout << "continue " << r.param << " from " << r.from << " to " << r.to << ": "
            << r.branches.size() << " branch(es), " << r.points.size() << " points\n";
  printBranchEnds(r);
  for (const auto& f : r.families)
    std::cout << "  family " << f.id << " (branch " << f.branch << "): " << f.cause << "\n";
  for (const auto& s : r.special)
    std::cout << "  " << s.type << " at " << r.param << " = " << roundTripText(s.at.value)
              << " (branch " << s.at.branch << "): " << s.detail << "\n";
  printCycles(r, cycle_budget);
  std::cout << "files in " << dir << "\n";
}

// The fold and Hopf points found in key1 at key2 = v2 (every locked state at lo1 followed) and
// their curves over the map (those not on a curve already in `curves`), appended to it.
void curvesFromRow(ContinueOptions o, const std::string& key2, double v2, double lo2, double hi2,
                   const P1Range& range, std::vector<FoldCurve>& curves) {
  ContinueOptions row = o;
  row.sets.push_back(key2 + "=" + roundTripText(v2));
  SlowFlowContinuationSpec spec;
  spec.params = paramsAt(row);
  spec.from = *o.from, spec.to = o.to;
  spec.settings = settingsFor(o, spec.from);
  spec.cycles = false;
  spec.params2 = paramsAt2(o);
  spec.from2 = v2, spec.to2 = hi2;
  spec.settings2 = curveSettings(lo2, hi2);
  spec.range1 = range;
  spec.known_curves = curves;
  try {
    const ContinuationResult r = continueSlowFlow(spec);
    curves.insert(curves.end(), r.fold_curves.begin(), r.fold_curves.end());
  } catch (const NoLockedState&) {
    // no locked state in this row: no curve starts here
  }
}

}  // namespace

void checkBoundaryKeys(const std::string& rig_path, const std::vector<std::string>& sets,
                       const std::string& key1, double lo1, double hi1, const std::string& key2,
                       double lo2, double hi2) {
  ContinueOptions o;
  o.rig_path = rig_path, o.sets = sets;
  o.param = key1, o.from = lo1, o.to = hi1;
  startValue(o);  // key1 must change the slow flow
  o.param = key2, o.from = lo2, o.to = hi2;
  startValue(o);  // and key2
}

std::vector<FoldCurve> boundaryCurves(const std::string& rig_path,
                                      const std::vector<std::string>& sets, const std::string& key1,
                                      double lo1, double hi1, const std::string& key2, double lo2,
                                      double hi2) {
  checkBoundaryKeys(rig_path, sets, key1, lo1, hi1, key2, lo2, hi2);
  ContinueOptions o;
  o.rig_path = rig_path, o.sets = sets, o.param = key1, o.from = lo1, o.to = hi1;
  o.fold_key = key2, o.to2 = hi2;
  // the curves a little past the map's edges in key1 (so that they reach them), not beyond
  constexpr double kRangeMargin = 0.05;
  const double margin = kRangeMargin * std::abs(hi1 - lo1);
  const P1Range range{std::min(lo1, hi1) - margin, std::max(lo1, hi1) + margin};
  std::vector<FoldCurve> curves;
  for (double f : {1.0 / 6, 0.5, 5.0 / 6})
    curvesFromRow(o, key2, lo2 + f * (hi2 - lo2), lo2, hi2, range, curves);
  mergeCurves(curves, std::abs(hi1 - lo1), std::abs(hi2 - lo2));
  return curves;
}

CLI::App* addContinueCommand(CLI::App& app) {
  ContinueOptions& opt = options();
  CLI::App* c = app.add_subcommand(
      "continue",
      "follow locked states in one rig key, the slow flow's fixed points or (--model full) the "
      "full model's periodic orbits: stability, folds, Hopf and torus points, branch points, "
      "border crossings");
  c->add_option("RIG", opt.rig_path, "rig file (YAML); default: the built-in rig");
  c->add_option("--model", opt.model,
                "slow (the slow flow's locked states) or full (the full model's periodic orbits, "
                "docs/continuation.md)")
      ->check(CLI::IsMember({"slow", "full"}))
      ->capture_default_str();
  c->add_option("--set", opt.sets, "override a rig key (as in run); repeatable")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  c->add_option("--param", opt.param, "the rig key to vary, e.g. metronomes.1.alpha")->required();
  addNumber(c, "--to", opt.to, kAnyFinite, "the other end of the parameter range")->required();
  addNumber(c, "--from", opt.from, kAnyFinite, "the start value (default: the rig's value of KEY)");
  c->add_option("--start", opt.start,
                "the start state A_1,..,A_N,psi_2,..,psi_N (default: the "
                "rig's start, integrated until it settles)");
  addNumber(c, "--step", opt.step, kPositive,
            "first step, in KEY's units (default |to - from| / 100); steps then adapt");
  addInteger(c, "--max-points", opt.max_points, 2, kMaxContinuationPoints,
             "points per direction of each branch")
      ->default_str(std::to_string(opt.max_points));
  c->add_flag("--all", opt.all, "every locked state at the start value (Newton from a grid)");
  c->add_option("--out", opt.out, "output directory (default runs/<rig name>-continue)");
  c->add_flag("-q,--quiet", opt.quiet, "no summary on stdout");
  addStrictFlag(c, opt.strict);
  c->add_flag("--no-cycles", opt.no_cycles,
              "do not follow the limit cycle born at each Hopf point (cycles.csv)");
  addInteger(c, "--cycle-points", opt.cycle_points, 2, kMaxContinuationPoints,
             "points of each limit cycle's branch at most")
      ->default_str(std::to_string(opt.cycle_points));
  CLI::Option* fold = c->add_option("--fold", opt.fold_key,
                                    "a second rig key: continue every fold and Hopf point found in "
                                    "KEY in (KEY, KEY2), from KEY2's value in the rig -> "
                                    "fold_curve.csv, hopf_curve.csv, fold_curve.png");
  addNumber(c, "--to2", opt.to2, kAnyFinite, "KEY2's other end (with --fold)")->needs(fold);
  fold->needs("--to2");
  c->footer(
      "Files in --out DIR: branches.csv, bifurcations.json, branches.png, cycles.csv, "
      "summary.json; with "
      "--fold also fold_curve.csv, hopf_curve.csv, fold_curve.png (see "
      "docs/continuation.md).\nExit codes: 0 success; 2 bad command line or rig (nothing "
      "written); 1 anything else.");
  return c;
}

int continueCommand() {
  return continueCommand(options());
}

ContinuationResult slowFlowContinuation(const ContinueOptions& opt) {
  requireSlowFlow(loadContinueRig(opt, {}), rigDisplay(opt));
  const double from = startValue(opt);
  std::string how;
  const SlowFlowContinuationSpec spec = slowFlowSpec(opt, from, how);
  ContinuationResult result;
  try {
    result = continueSlowFlow(spec);
  } catch (const NoLockedState& e) {
    throw UsageError(std::string(e.what()) + " at " + opt.param + " = " + roundTripText(from) +
                     (opt.all ? "" : " (" + how + ")"));
  } catch (const std::invalid_argument& e) {  // the slow flow at a value on the way: not finite
    throw UsageError("--param " + opt.param + " from " + roundTripText(from) + " to " +
                     roundTripText(opt.to) + ": " + e.what() +
                     " on the way (the range leaves the range of the numbers); " +
                     "choose a --to nearer the start");
  }
  result.param = opt.param;
  result.param2 = opt.fold_key;
  result.start = opt.all ? "--all: every locked state Newton finds from a grid of seeds" : how;
  return result;
}

int continueCommand(const ContinueOptions& opt) {
  loadContinueRig(opt, {});  // a bad rig is said as such before its ranges are judged
  checkSensibleRanges(rigText(opt), rigDisplay(opt), opt.sets, opt.strict);
  if (opt.model == "full") return continueFullCommand(opt);
  const ContinuationResult result = slowFlowContinuation(opt);
  const Rig rig = loadContinueRig(opt, {opt.param + "=" + roundTripText(result.from)});
  const OutputDir dir(outDir(opt, rig));
  writeContinuation(dir, result, rig.name);
  if (!opt.quiet) printSummary(result, dir.path(), opt.cycle_points);
  return kSuccess;
}

}  // namespace metrosync::cli
