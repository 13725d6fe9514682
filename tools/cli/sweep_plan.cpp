#include "tools/cli/sweep_plan.h"

#include <set>

#include "base/number_text.h"
#include "tools/cli/commands.h"
#include "tools/cli/continue.h"
#include "tools/cli/engines.h"
#include "tools/cli/network_sweep.h"
#include "tools/cli/option_keys.h"
#include "tools/cli/range_warnings.h"
#include "tools/cli/sweep_point_run.h"
#include "tools/report/outputs.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

namespace {

// Up to this many axes every corner of the grid is loaded before the sweep (2^axes rigs).
constexpr size_t kMaxCornerAxes = 8;

// --resume holds two bits a grid point (which are done, which were seen in regimes.csv): at most
// this many bytes, 2^30 points (docs/rig-limits.md).
constexpr double kMaxResumeBytes = 256.0 * 1024 * 1024;

// --resume: the memory it will need, stated and refused before anything is read or written.
void checkResumeMemory(const SweepOptions& opt, const SweepGrid& grid) {
  const double bytes = static_cast<double>(grid.size()) / 4.0;  // two bits a point
  if (!opt.resume || bytes <= kMaxResumeBytes) return;
  throw UsageError("--resume: the grid's " + std::to_string(grid.size()) + " points need about " +
                   numberText(bytes) +
                   " bytes of memory to know which are done (two bits a point), above the limit "
                   "of " +
                   numberText(kMaxResumeBytes) +
                   " bytes (docs/rig-limits.md): resume a smaller grid, or run it afresh "
                   "without --resume");
}

// The grid checked in bounded time, before any file: the point at every corner of the grid and
// at each axis's every end (the rig loader's checks are ranges, so a value inside an axis that
// passes at both its ends passes everywhere; the mass and size budgets grow with a value
// monotonically). The points in between are loaded when they run; a point that fails there after
// all is recorded as failed with the loader's message and the sweep goes on. Returns the engine,
// the same at every point (no --vary names one).
const Engine* checkGrid(const SweepPlan& plan, const SweepOptions& opt) {
  const std::vector<SweepAxis>& axes = plan.grid.axes();
  std::set<long> probes;
  auto index = [&](const std::vector<bool>& high) {
    long g = 0;
    for (size_t a = 0; a < axes.size(); ++a)
      g = g * axes[a].count + (high[a] ? axes[a].count - 1 : 0);
    return g;
  };
  if (axes.size() <= kMaxCornerAxes) {
    for (long corner = 0; corner < (1L << axes.size()); ++corner) {
      std::vector<bool> high(axes.size());
      for (size_t a = 0; a < axes.size(); ++a) high[a] = (corner >> (axes.size() - 1 - a)) & 1;
      probes.insert(index(high));
    }
  } else {  // 2^axes corners would be too many: both ends of each axis, the others low or high
    for (bool rest : {false, true})
      for (size_t a = 0; a <= axes.size(); ++a) {
        std::vector<bool> high(axes.size(), rest);
        if (a < axes.size()) high[a] = !rest;
        probes.insert(index(high));
      }
  }
  const Engine* engine = nullptr;
  for (long g : probes) {
    const PointInput in = loadPoint(plan.text, opt, plan.grid, g);
    if (static_cast<int>(in.rig.metronomes.size()) != plan.n)
      throw UsageError("--vary changes the number of metronomes at grid point " +
                       std::to_string(g));
    if (!engine) engine = in.engine;
  }
  return engine;
}

// --boundaries: a slow-flow map over two ranges (the curves are drawn in its plane).
void checkBoundaries(const SweepOptions& opt, const SweepPlan& plan) {
  const std::vector<SweepAxis>& axes = plan.grid.axes();
  if (plan.manifest.model != "slow")
    throw UsageError(
        "--boundaries: the fold and Hopf curves are the slow flow's; use --model slow");
  if (axes.size() != 2 || axes[0].count < 2 || axes[1].count < 2)
    throw UsageError("--boundaries: needs a map over two keys (two --vary of 2 or more values)");
  for (const SweepAxis& a : axes)
    if (a.spec.find(':') == std::string::npos)
      throw UsageError("--boundaries: --vary " + a.key + "=" + a.spec +
                       ": give a range FROM:TO:COUNT (the curves are continuous in both keys)");
  try {
    checkBoundaryKeys(opt.rig_path, opt.sets, axes[0].key, axes[0].value(0),
                      axes[0].value(axes[0].count - 1), axes[1].key, axes[1].value(0),
                      axes[1].value(axes[1].count - 1));
  } catch (const UsageError& e) {
    throw UsageError(std::string("--boundaries: ") + e.what());
  }
}

// The --vary and --random keys resolved against the rig (docs/keys.md), in that order: a bad key
// stops here with the same words as a --set of it, and so do two options that set one rig key.
std::vector<OptionKey> sweepKeys(const SweepOptions& opt, const std::string& text) {
  const std::string name = displayName(opt);
  const KeyedRig rig{text, name, opt.sets};
  std::vector<OptionKey> keys;
  for (const auto& v : opt.vary) keys.push_back(resolveOptionKey(rig, "--vary", v, true));
  for (const auto& r : opt.random) keys.push_back(resolveOptionKey(rig, "--random", r, true));
  refuseSharedKeys(keys);
  return keys;
}

// --basin-samples S --random ... [--seed N]: the keys drawn at every point (`resolved`: those of
// sweepKeys), kept in the grid (the manifest) so that --resume and merge check them. Throws
// UsageError.
std::vector<RandomKey> planPointBasin(const SweepOptions& opt, SweepGrid& grid,
                                      const std::vector<OptionKey>& resolved) {
  if (opt.basin_samples == 0 && opt.random.empty()) return {};
  if (opt.basin_samples < 1 || opt.random.empty())
    throw UsageError("--basin-samples S (S >= 1) and --random KEY=FROM:TO go together");
  std::vector<RandomKey> keys;
  for (size_t i = 0; i < opt.random.size(); ++i) {
    const RigKey& k = resolved[opt.vary.size() + i].key;
    keys.push_back(parseRandom(opt.random[i], isPhaseName(k.key.leaf())));
  }
  grid.setBasin({opt.basin_samples, opt.seed, opt.random});
  return keys;
}

}  // namespace

// The fold and Hopf curves over the map's two ranges (boundaryCurves, tools/cli/continue.h).
std::vector<continuation::FoldCurve> mapBoundaries(const SweepOptions& opt, const SweepPlan& plan) {
  const SweepAxis &x = plan.grid.axes()[0], &y = plan.grid.axes()[1];
  return boundaryCurves(opt.rig_path, opt.sets, x.key, x.value(0), x.value(x.count - 1), y.key,
                        y.value(0), y.value(y.count - 1));
}

// The overrides of grid point g's basin sample k: the point's, then the draws of (seed, k).
std::vector<std::string> basinSampleOverrides(const SweepGrid& grid,
                                              const std::vector<RandomKey>& keys, long g, long k) {
  std::vector<std::string> point = grid.overrides(g);
  const std::vector<double> v = drawSample(keys, grid.basin().seed, k);
  for (size_t i = 0; i < keys.size(); ++i)
    point.push_back(keys[i].key + "=" + sweepValueText(v[i]));
  return point;
}

SweepPlan planSweep(const SweepOptions& opt) {
  std::vector<SweepAxis> axes;
  for (const auto& v : opt.vary) axes.push_back(parseVary(v));
  SweepPlan plan;
  plan.grid = SweepGrid(std::move(axes), opt.force ? kMaxForcedGridPoints : kMaxGridPoints);
  checkResumeMemory(opt, plan.grid);
  plan.map_axes = mapAxes(plan.grid, opt.map);
  plan.shard = opt.shard.empty() ? SweepShard{} : parseShard(opt.shard);
  // the rig, its keys, and every grid point's rig: a bad key or value stops here, before any file
  plan.text = sweepRigText(opt);
  std::optional<Network> net;
  plan.base = loadSweepRig(plan.text, displayName(opt), opt.sets, &net);
  checkSensibleRanges(plan.text, displayName(opt), opt.sets, opt.strict);  // the base rig only
  plan.random = planPointBasin(opt, plan.grid, sweepKeys(opt, plan.text));
  plan.n = static_cast<int>(plan.base.metronomes.size());
  if (net && !opt.keep.empty())
    throw UsageError("--keep envelope: not for a network of platforms (docs/sweep-points.md)");
  plan.mine = shardSize(plan.grid, plan.shard);
  const Engine* engine = checkGrid(plan, opt);
  for (bool high : {false, true}) {  // the drawn keys at their ends, at grid point 0
    if (plan.random.empty()) break;
    std::vector<std::string> point = plan.grid.overrides(0);
    for (const RandomKey& r : plan.random) {
      const double v = high ? r.to : r.from;
      point.push_back(r.key + "=" + sweepValueText(r.angle ? wrapToTwoPi(v) : v));
    }
    loadPointRig(plan.text, opt, point,
                 "grid point 0 with --random at " + std::string(high ? "TO" : "FROM"), "--random");
  }
  SweepManifest& m = plan.manifest;
  m.model = engine->model();
  m.engine = engine->name();
  m.rig_path = opt.rig_path;
  m.rig_name = plan.base.name;
  m.rig_text = plan.text;
  m.sets = opt.sets;
  m.metronomes = plan.n;
  m.grid = plan.grid;
  m.shard = plan.shard;
  plan.path = opt.out.empty() ? defaultOutputDir(plan.base.name, "sweep", opt.sets) : opt.out;
  plan.regimes_path = plan.path + "/regimes.csv";
  if (opt.boundaries) checkBoundaries(opt, plan);
  return plan;
}

}  // namespace metrosync::cli
