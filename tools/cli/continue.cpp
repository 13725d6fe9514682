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
#include "sim/analysis/continuation/arclength.h"
#include "sim/analysis/continuation/fold_curve.h"
#include "sim/analysis/continuation/result.h"
#include "sim/analysis/continuation/start_states.h"
#include "tools/cli/commands.h"
#include "tools/cli/continue_full.h"
#include "tools/cli/number_option.h"
#include "tools/cli/option_keys.h"
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

// A located fold or Hopf point, for --fold.
struct FoldSeed {
  int reference;
  BranchPoint at;
  CurveKind kind;
};

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

// The slow flow's inputs: equal when KEY has no effect on it.
bool sameSlowFlow(const ScaledParams& a, const ScaledParams& b) {
  return a.law == b.law && a.mu == b.mu && a.c == b.c && a.nu == b.nu && a.J == b.J &&
         a.theta_c == b.theta_c && a.alpha == b.alpha && a.locked == b.locked;
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
// --to 1e308) is refused naming `which` option gave it.
ScaledParams finiteScaledAt(const ContinueOptions& opt, double value, const std::string& which) {
  const ScaledParams p = scaledAt(opt, {opt.param}, {value});
  const std::pair<const char*, const std::vector<double>*> lists[] = {
      {"nu", &p.nu}, {"J", &p.J}, {"theta_c", &p.theta_c}, {"alpha", &p.alpha}, {"zeta", &p.zeta}};
  std::string bad = std::isfinite(p.mu) ? "" : "mu";
  if (!std::isfinite(p.c)) bad = "c";
  for (const auto& [name, v] : lists)
    for (double x : *v)
      if (!std::isfinite(x)) bad = name;
  if (!bad.empty())
    throw UsageError(which + ": " + opt.param + " = " + roundTripText(value) +
                     " makes the scaled " + bad +
                     " infinite or undefined; choose a value nearer the rig's");
  return p;
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

int largest(const std::vector<Cd>& z) {
  int r = 0;
  for (size_t i = 1; i < z.size(); ++i)
    if (std::abs(z[i]) > std::abs(z[r])) r = static_cast<int>(i);
  return r;
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
  const double span = s.p_max - s.p_min;
  s.step = opt.step > 0 ? opt.step : span / 100;
  s.step_max = std::max(s.step, span / 25);
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

void foldCurves(const ContinueOptions& opt, double from2, const std::vector<FoldSeed>& folds,
                ContinuationResult& result) {
  ContinueOptions second = opt;
  second.to = opt.to2, second.step = 0;
  ContinuationSettings s = settingsFor(second, from2);
  // the curve's arclength is mostly in KEY and the state (O(1)), not only KEY2's span
  constexpr double kFoldStep = 0.005, kFoldStepMax = 0.05;
  s.step = std::max(s.step, kFoldStep);
  s.step_max = std::max(s.step_max, kFoldStepMax);
  result.param2 = opt.fold_key;
  for (const FoldSeed& f : folds) {
    const int n = static_cast<int>(f.at.y.size()) - 1;
    const auto follow = f.kind == CurveKind::Fold ? continueFold : continueHopf;
    result.fold_curves.push_back(
        follow(paramsAt2(opt), f.reference, f.at.y.head(n), f.at.p(), from2, f.at.region, s, {}));
  }
}

std::string outDir(const ContinueOptions& opt, const Rig& rig) {
  return opt.out.empty() ? "runs/" + rig.name + "-continue" : opt.out;
}

// Whether the state (A, psi) at parameter p lies on a branch already in r (between two of its
// consecutive points, linearly interpolated).
bool alreadyFollowed(const ContinuationResult& r, const std::vector<double>& A,
                     const std::vector<double>& psi, double p) {
  constexpr double kSame = 1e-3;  // far above the interpolation error of a step, far below a gap
  for (size_t k = 1; k < r.points.size(); ++k) {
    const ResultPoint &a = r.points[k - 1], &b = r.points[k];
    if (a.branch != b.branch || (a.value - p) * (b.value - p) > 0 || a.value == b.value) continue;
    const double w = (p - a.value) / (b.value - a.value);
    double d = 0;
    for (size_t i = 0; i < A.size(); ++i)
      d = std::max(d, std::abs(A[i] - (a.A[i] + w * (b.A[i] - a.A[i]))));
    for (size_t j = 0; j < psi.size(); ++j)
      d = std::max(
          d, std::abs(std::remainder(psi[j] - (a.psi[j] + w * (b.psi[j] - a.psi[j])), 2 * kPi)));
    if (d < kSame) return true;
  }
  return false;
}

// Whether a cycle from the Hopf point at parameter p is already in r (the same Hopf point found
// on another branch, or again from the other side).
bool cycleFollowed(const ContinuationResult& r, double p) {
  constexpr double kSameHopf = 1e-7;  // Hopf points are located to ~1e-11 in the parameter
  for (const ResultCycle& c : r.cycles)
    if (std::abs(c.hopf_value - p) <= kSameHopf * std::max(1.0, std::abs(p))) return true;
  return false;
}

void record(const ContinueOptions& opt, const SlowFlowProblem& prob,
            const std::vector<Branch>& branches, const ContinuationSettings& settings,
            ContinuationResult& result, std::vector<FoldSeed>& folds) {
  appendBranches(prob, branches, result);
  for (const Branch& b : branches)
    for (const Bifurcation& e : b.special) {
      if (e.type == BifurcationType::Fold)
        folds.push_back({prob.reference(), e.point, CurveKind::Fold});
      if (e.type != BifurcationType::Hopf) continue;
      folds.push_back({prob.reference(), e.point, CurveKind::Hopf});
      if (opt.no_cycles || cycleFollowed(result, e.point.p())) continue;
      result.cycles.push_back(followSlowFlowCycle(prob, e.point, settings));
      result.cycles.back().id = static_cast<int>(result.cycles.size()) - 1;
    }
}

void followAll(const ContinueOptions& opt, const ScaledParams& sp, double from,
               const ContinuationSettings& settings, ContinuationResult& result,
               std::vector<FoldSeed>& folds) {
  int ref = 0;
  while (ref < static_cast<int>(sp.locked.size()) && sp.locked[ref]) ++ref;
  if (ref == static_cast<int>(sp.locked.size())) throw UsageError("every metronome is locked");
  const SlowFlowProblem prob(paramsAt(opt), from, ref);
  const std::vector<Vec> states = allLockedStates(prob, from);
  if (states.empty())
    throw UsageError("--all: Newton finds no locked state at " + opt.param + " = " +
                     roundTripText(from));
  result.start = "--all: " + std::to_string(states.size()) +
                 " locked state(s) found by Newton from a grid of seeds";
  for (const Vec& x : states) {
    if (alreadyFollowed(result, prob.amplitudes(x), prob.phaseDifferences(x), from)) continue;
    // the largest amplitude as the reference: z_r real stays regular while z_r does not vanish
    const std::vector<Cd> z = prob.unpack(x);
    const SlowFlowProblem mine(paramsAt(opt), from, largest(z));
    record(opt, mine, continueFrom(mine.system(), mine.pack(z, prob.omega(x)), from, settings),
           settings, result, folds);
  }
}

void printSummary(const ContinuationResult& r, const std::string& dir) {
  std::cout << "continue " << r.param << " from " << r.from << " to " << r.to << ": "
            << r.branches.size() << " branch(es), " << r.points.size() << " points\n";
  for (const auto& s : r.special)
    std::cout << "  " << s.type << " at " << r.param << " = " << roundTripText(s.at.value)
              << " (branch " << s.at.branch << "): " << s.detail << "\n";
  std::cout << "files in " << dir << "\n";
}

// Whether a curve of `kind` in `curves` passes within kSameCurve of (p1, p2) (interpolated
// between consecutive points bracketing p2).
bool onACurve(const std::vector<FoldCurve>& curves, CurveKind kind, double p1, double p2,
              double span1) {
  constexpr double kSameCurve = 1e-3;  // of key1's range: far above a curve's interpolation error
  for (const FoldCurve& c : curves) {
    if (c.kind != kind) continue;
    for (size_t k = 1; k < c.points.size(); ++k) {
      const FoldCurvePoint &a = c.points[k - 1], &b = c.points[k];
      if ((a.p2 - p2) * (b.p2 - p2) > 0 || a.p2 == b.p2) continue;
      const double w = (p2 - a.p2) / (b.p2 - a.p2);
      if (std::abs(a.p1 + w * (b.p1 - a.p1) - p1) < kSameCurve * span1) return true;
    }
  }
  return false;
}

// The fold and Hopf points found in key1 at key2 = v2 (every locked state at lo1 followed).
std::vector<FoldSeed> pointsInRow(ContinueOptions o, const std::string& key2, double v2,
                                  double lo1) {
  o.sets.push_back(key2 + "=" + roundTripText(v2));
  const ScaledParams sp = computeScaled(loadContinueRig(o, {o.param + "=" + roundTripText(lo1)}));
  ContinuationResult result;
  std::vector<FoldSeed> seeds;
  try {
    followAll(o, sp, lo1, settingsFor(o, lo1), result, seeds);
  } catch (const UsageError&) {
    return {};  // no locked state in this row
  }
  return seeds;
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
  o.all = true, o.no_cycles = true, o.fold_key = key2, o.to2 = hi2;
  ContinuationSettings s2;
  s2.p_min = std::min(lo2, hi2), s2.p_max = std::max(lo2, hi2);
  // the curve's arclength is mostly in key1 and the state (O(1)), not only key2's span
  constexpr double kCurveStep = 0.005, kCurveStepMax = 0.05;
  s2.step = std::max((s2.p_max - s2.p_min) / 100, kCurveStep);
  s2.step_max = std::max((s2.p_max - s2.p_min) / 25, kCurveStepMax);
  // the curves a little past the map's edges in key1 (so that they reach them), not beyond
  constexpr double kRangeMargin = 0.05;
  const double margin = kRangeMargin * std::abs(hi1 - lo1);
  const P1Range range{std::min(lo1, hi1) - margin, std::max(lo1, hi1) + margin};
  std::vector<FoldCurve> curves;
  for (double f : {1.0 / 6, 0.5, 5.0 / 6}) {
    const double v2 = lo2 + f * (hi2 - lo2);
    for (const FoldSeed& seed : pointsInRow(o, key2, v2, lo1)) {
      if (onACurve(curves, seed.kind, seed.at.p(), v2, std::abs(hi1 - lo1))) continue;
      const int n = static_cast<int>(seed.at.y.size()) - 1;
      const auto follow = seed.kind == CurveKind::Fold ? continueFold : continueHopf;
      curves.push_back(follow(paramsAt2(o), seed.reference, seed.at.y.head(n), seed.at.p(), v2,
                              seed.at.region, s2, range));
    }
  }
  return curves;
}

CLI::App* addContinueCommand(CLI::App& app) {
  ContinueOptions& opt = options();
  CLI::App* c = app.add_subcommand(
      "continue",
      "follow the slow flow's locked states in one rig key: stability, folds, Hopf "
      "points, branch points, border crossings");
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
  addNumber(c, "--step", opt.step, kPositive, "first arclength step (default |to - from| / 100)");
  addInteger(c, "--max-points", opt.max_points, 2, kMaxContinuationPoints,
             "points per direction of each branch")
      ->default_str(std::to_string(opt.max_points));
  c->add_flag("--all", opt.all, "every locked state at the start value (Newton from a grid)");
  c->add_option("--out", opt.out, "output directory (default runs/<rig name>-continue)");
  c->add_flag("-q,--quiet", opt.quiet, "no summary on stdout");
  c->add_flag("--no-cycles", opt.no_cycles,
              "do not follow the limit cycle born at each Hopf point (cycles.csv)");
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

Rig loadContinueRig(const ContinueOptions& opt, const std::vector<std::string>& extra) {
  std::vector<std::string> o = opt.sets;
  o.insert(o.end(), extra.begin(), extra.end());
  try {
    return opt.rig_path.empty() ? defaultRig(o) : loadRigFile(opt.rig_path, o);
  } catch (const RigError& e) {
    std::string what = e.what();
    for (const auto& x : extra)
      for (size_t at = what.find("--set " + x); at != std::string::npos;
           at = what.find("--set " + x, at))
        what.replace(at, 5, "--param");
    throw RigError(what);
  }
}

int continueCommand(const ContinueOptions& opt) {
  if (opt.model == "full") return continueFullCommand(opt);
  const double from = startValue(opt);
  const double from2 = opt.fold_key.empty() ? 0.0 : secondStart(opt);
  const Rig rig = loadContinueRig(opt, {opt.param + "=" + roundTripText(from)});
  const ScaledParams sp = computeScaled(rig);
  const ContinuationSettings settings = settingsFor(opt, from);
  ContinuationResult result;
  result.param = opt.param, result.from = from, result.to = opt.to;
  result.metronomes = static_cast<int>(sp.nu.size());
  result.theta_c = sp.theta_c;
  std::vector<FoldSeed> folds;
  try {
    if (opt.all) {
      followAll(opt, sp, from, settings, result, folds);
    } else {
      const std::vector<Cd> z = startState(opt, sp, result.start);
      const SlowFlowProblem prob(paramsAt(opt), from, largest(z));
      const auto x = solveLocked(prob, prob.pack(z, prob.omegaGuess(from, z)), from);
      if (!x) throw UsageError("Newton does not converge to a locked state from " + result.start);
      record(opt, prob, continueFrom(prob.system(), *x, from, settings), settings, result, folds);
    }
    if (!opt.fold_key.empty()) foldCurves(opt, from2, folds, result);
  } catch (const std::invalid_argument& e) {  // the slow flow at a value on the way: not finite
    throw UsageError("--param " + opt.param + " from " + roundTripText(from) + " to " +
                     roundTripText(opt.to) + ": " + e.what() +
                     " on the way (the range leaves the range of the numbers); " +
                     "choose a --to nearer the start");
  }
  const OutputDir dir(outDir(opt, rig));
  writeContinuation(dir, result, rig.name);
  if (!opt.quiet) printSummary(result, dir.path());
  return kSuccess;
}

}  // namespace metrosync::cli
