#include "tools/cli/sweep.h"

#include <signal.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "models/scaling.h"
#include "sim/analysis/basin.h"
#include "sim/analysis/regime.h"
#include "sim/analysis/sweep.h"
#include "tools/cli/commands.h"
#include "tools/cli/continue.h"
#include "tools/cli/engines.h"
#include "tools/cli/network_sweep.h"
#include "tools/cli/option_keys.h"
#include "tools/report/envelope_store.h"
#include "tools/report/folder_lock.h"
#include "tools/report/outputs.h"
#include "tools/report/plot.h"
#include "tools/report/progress_log.h"
#include "tools/report/sweep_files.h"
#include "tools/report/sweep_maps.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// CPU seconds of the calling thread (a point runs on one thread): on a shared machine the measure
// of what a point costs, where wall time also counts the other processes.
double threadCpuSeconds() {
  timespec ts{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::string fmt(double v, const char* f = "%.4g") {
  char buf[40];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string joined(const std::vector<std::string>& v, const std::string& sep = ", ") {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

const char* modelTitle(const std::string& model) {
  return model == "full" ? "full model" : "slow flow";
}

// The files a sweep writes (besides the maps), for removing stale ones.
const std::vector<std::string>& sweepFileNames() {
  static const std::vector<std::string> names = {"regimes.csv", "sweep.json", "timings.csv",
                                                 kEnvelopeStoreName};
  return names;
}

// Removes the sweep's own files left in `dir` by an earlier command, and the temporary files of
// commands that are no longer running; run's files too (every file in DIR then belongs to this
// command).
void removeStaleSweepOutputs(const OutputDir& dir) {
  dir.removeStaleOutputs();
  std::vector<std::string> names = sweepFileNames();
  for (const auto& m : sweepMapNames()) names.push_back(m);
  std::error_code ec;
  for (const auto& name : names) fs::remove(dir.file(name), ec);
  for (const auto& entry : fs::directory_iterator(dir.path(), ec)) {
    const std::string f = entry.path().filename().string();
    if (isSweepSliceMapName(f)) {  // regimes--KEY=VALUE.png: an N-D sweep's maps
      fs::remove(entry.path(), ec);
      continue;
    }
    for (const auto& name : names) {
      const std::string prefix = "." + name + ".";
      if (f.compare(0, prefix.size(), prefix) != 0 || f.size() < 6 ||
          f.compare(f.size() - 5, 5, ".part") != 0)
        continue;
      // ".NAME.<pid>.part" or ".NAME.<suffix>.<pid>.part": the pid is the last number
      const std::string core = f.substr(0, f.size() - 5);
      const std::string pid_text = core.substr(core.rfind('.') + 1);
      if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos)
        continue;
      const long pid = std::stol(pid_text);
      if (pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
        fs::remove(entry.path(), ec);
    }
  }
}

// ---- the rig and the grid, checked before anything is written --------------------------------

// Up to this many axes every corner of the grid is loaded before the sweep (2^axes rigs).
constexpr size_t kMaxCornerAxes = 8;

std::string displayName(const SweepOptions& opt) {
  return opt.rig_path.empty() ? "<default rig>" : opt.rig_path;
}

// One grid point, ready to run.
struct PointInput {
  Rig rig;
  ScaledParams scaled;
  const Engine* engine = nullptr;  // the same at every point (no --vary names one)
  std::optional<Network> net;      // a network of platforms (tools/cli/network_sweep.h)
};

// The model --model asks for: as given, else the --engine's, else the slow flow.
std::string requestedModel(const SweepOptions& opt) {
  if (!opt.model.empty()) return opt.model;
  return opt.engine.empty() ? "slow" : "";
}

// Is the rig text a network of platforms? Decided once per thread for the text it last saw: every
// point of a sweep (and every basin sample) has the same text, and parsing it once more per point
// cost 1.5% of a slow-flow point (docs/bench/sweep-throughput.md). --set and --vary cannot make a
// text a network: only the text's own `platforms` key does (yaml/network_loader.h).
bool isNetworkRig(const std::string& text) {
  thread_local std::string last_text;
  thread_local bool known = false, last = false;
  if (!known || text != last_text) {
    last = isNetworkText(text);
    last_text = text;
    known = true;
  }
  return last;
}

// The rig of one point: the base rig, --set, then the point's KEY=VALUE (keys as the user typed
// them: the loader resolves them, docs/keys.md); checked like `run` checks its rig. `where` names
// the point ("grid point 12 (...)"); throws RigError naming it.
PointInput loadPointRig(const std::string& text, const SweepOptions& opt,
                        const std::vector<std::string>& point, const std::string& where,
                        const std::string& source = "--vary point") {
  std::vector<std::string> overrides = opt.sets;
  overrides.insert(overrides.end(), point.begin(), point.end());
  PointInput in;
  try {
    if (isNetworkRig(text)) in.net = loadSweepNetwork(text, displayName(opt), overrides);
    in.rig = in.net ? networkSweepRig(*in.net) : loadRigText(text, displayName(opt), overrides);
  } catch (const RigError& e) {
    // the loader calls every override --set; the point's own ones come from --vary
    std::string what = e.what();
    for (const auto& o : point)
      for (size_t at = what.find("--set " + o); at != std::string::npos;
           at = what.find("--set " + o, at))
        what.replace(at, 6 + o.size(), source + " " + o);
    throw RigError(what + "\n  at " + where);
  }
  if (in.net) {  // docs/networks.md
    in.engine = &networkSweepEngine(opt.engine, opt.model, *in.net, displayName(opt));
    return in;
  }
  // checks --engine against --model and the point's integrator
  in.engine = &chooseEngine(opt.engine, requestedModel(opt), in.rig, displayName(opt));
  try {
    in.scaled = computeScaled(in.rig);
  } catch (const std::invalid_argument& e) {
    throw RigError(displayName(opt) + ": " + e.what() + "\n  at " + where);
  }
  return in;
}

PointInput loadPoint(const std::string& text, const SweepOptions& opt, const SweepGrid& grid,
                     long g) {
  const std::vector<std::string> point = grid.overrides(g);
  return loadPointRig(text, opt, point,
                      "grid point " + std::to_string(g) + " (" + joined(point) + ") of the sweep");
}

// ---- one point ---------------------------------------------------------------------------------

// Keeps what the verdict needs; a stop request (SIGINT, SIGTERM) interrupts the run.
struct PointSink : RunSink {
  PointSink(double tau_end, double epsilon) : window(tau_end, epsilon) {}
  void envelopeRow(const EnvelopeRow& row) override {
    window.add(row);
    if (keep) kept.push_back(formatEnvelopeRow(row));
    if (FileSink::stopRequested()) throw RunInterrupted(row.tau, "interrupted by a signal");
  }
  // the platform column (0 stuck): the `uncoupled` rule (full model)
  void trajectoryRow(const std::vector<double>& row) override {
    if (row.size() > 2) window.platformMode(static_cast<int>(row.back()), row[1] / x_unit);
  }
  void eventRow(const char*, const std::vector<double>& row) override { trajectoryRow(row); }
  RegimeWindow window;
  double x_unit = 1.0;  // trajectory x per scaled x
  bool keep = false;    // --keep envelope
  std::vector<std::string> kept;
};

// The test hook METROSYNC_SWEEP_FAIL_AT=g1,g2,...: those grid points fail as a simulation
// failure would (no rig makes the engines fail on demand).
bool failureInjected(long g) {
  static const std::vector<long> points = [] {
    std::vector<long> v;
    const char* e = std::getenv("METROSYNC_SWEEP_FAIL_AT");
    std::stringstream ss(e ? e : "");
    std::string item;
    while (std::getline(ss, item, ','))
      if (!item.empty()) v.push_back(std::atol(item.c_str()));
    return v;
  }();
  return std::find(points.begin(), points.end(), g) != points.end();
}

// A network's point (tools/cli/network_sweep.h), with the test hook and the stop request.
std::optional<SweepPoint> runNetworkPoint(const PointInput& in, long g) {
  SweepPoint p = runNetworkSweepPoint(*in.net, *in.engine, g, failureInjected(g));
  if (FileSink::stopRequested()) return std::nullopt;
  return p;
}

std::optional<SweepPoint> runPoint(const PointInput& in, long g, bool keep) {
  if (in.net) return runNetworkPoint(in, g);
  const ScaledParams& sp = in.scaled;
  PointSink sink(sp.tau_end, sp.epsilon);
  // the `uncoupled` rule: the slow flow's averaged drive, the full model's own stick/slip
  if (in.engine->model() != "full") sink.window.setEnvelopePlatform(sp.law, sp.mu);
  sink.x_unit = in.rig.units == Units::Physical ? sp.x_scale_m : 1.0;
  sink.keep = keep;
  RunReport rep;
  const double engine_cpu0 = threadCpuSeconds();
  try {
    if (failureInjected(g))
      throw SimulationFailure{0.0, "failure injected by METROSYNC_SWEEP_FAIL_AT, a test hook"};
    rep = in.engine->run(in.rig, sink);
  } catch (const RunInterrupted&) {
    return std::nullopt;
  } catch (const SimulationFailure& f) {
    rep.complete = false;
    rep.failure = "stopped at t = " + fmt(f.t, "%.6g") +
                  (in.rig.units == Units::Physical ? " s" : "") + ": " + f.why;
  } catch (const std::exception& e) {
    rep.complete = false;
    rep.failure = e.what();
  }
  // an engine that turned the interruption into a failed report
  if (!rep.complete && FileSink::stopRequested()) return std::nullopt;

  const int n = static_cast<int>(sp.nu.size());
  SweepPoint p;
  p.index = g;
  p.complete = rep.complete;
  p.engine_cpu_seconds = threadCpuSeconds() - engine_cpu0;
  const EnvelopeRow last = sink.window.empty() ? rep.final_row : sink.window.last();
  if (static_cast<int>(last.A.size()) == n && static_cast<int>(last.psi.size()) == n - 1) {
    p.A = last.A;
    for (double v : last.psi) p.psi.push_back(wrapToTwoPi(v));
    p.r = std::isnan(last.r) ? orderParameter(last.A, last.psi) : last.r;
    p.tau = last.tau;
    if (sp.law == FrictionLaw::Coulomb) {  // |Z| = r sum_j A_j
      double sum = 0.0;
      for (double a : last.A) sum += a;
      p.s = sp.mu > 0 ? p.r * sum / sp.mu : std::numeric_limits<double>::infinity();
    }
  } else {
    p.A.assign(n, std::nan(""));
    p.psi.assign(n - 1, std::nan(""));
  }
  if (rep.complete) {
    const RegimeVerdict v = classifyRegime(sink.window, sp.theta_c, sp.locked);
    p.regime = regimeName(v);
    p.clusters = clusterText(v.cluster_sizes);
  } else {
    p.regime = "failed";
    p.message = rep.failure.empty() ? "the run stopped early" : rep.failure;
  }
  p.kept_rows = std::move(sink.kept);
  return p;
}

// A grid point that could not even be loaded (checkGrid loads only the grid's corners): failed,
// with the loader's message, and the sweep goes on.
SweepPoint unloadablePoint(long g, int n, const std::string& why) {
  SweepPoint p;
  p.index = g;
  p.complete = false;
  p.regime = "failed";
  p.message = why;
  p.engine_cpu_seconds = 0.0;  // no engine ran
  p.A.assign(n, std::nan(""));
  p.psi.assign(n > 0 ? n - 1 : 0, std::nan(""));
  return p;
}

// ---- progress on a terminal --------------------------------------------------------------------

class Progress {
 public:
  // on: the bar (stderr a terminal); log: a line every 10% instead (tools/report/progress_log.h)
  Progress(bool on, bool log, long total, long done_before)
      : on_(on), total_(total), done_(done_before), start_done_(done_before) {
    if (log)
      log_ = std::make_unique<ProgressLog>("sweep", "points", static_cast<double>(total),
                                           [](const std::string& l) { std::cerr << l << "\n"; });
  }

  void finished(bool failed) {
    ++done_;
    failed_ += failed;
    if (log_) log_->update(static_cast<double>(done_));
    if (!on_) return;
    const Clock::time_point now = Clock::now();
    if (done_ < total_ && now - last_ < std::chrono::milliseconds(200)) return;
    last_ = now;
    draw();
  }

  void done() {
    if (on_ && drawn_) std::cerr << "\n";
  }

 private:
  void draw() {
    const double elapsed = secondsSince(t0_);
    const long run = done_ - start_done_;
    const double rate = elapsed > 0 && run > 0 ? run / elapsed : 0.0;
    const double eta = rate > 0 ? (total_ - done_) / rate : -1.0;
    winsize ws{};
    const int width = ::ioctl(2, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 20 ? ws.ws_col - 1 : 79;
    // back to the start of the line, the bar, and clear what a longer bar left behind
    std::cerr << "\r" << progressText(done_, total_, failed_, rate, eta, width) << "\033[K"
              << std::flush;
    drawn_ = true;
  }

  bool on_;
  std::unique_ptr<ProgressLog> log_;
  long total_, done_, start_done_, failed_ = 0;
  bool drawn_ = false;
  Clock::time_point t0_ = Clock::now(), last_{};
};

// ---- summary
// -------------------------------------------------------------------------------------

std::string countsText(const std::map<long, SweepPoint>& points) {
  const auto counts = regimeCounts(points);
  std::string s;
  for (const auto& name : regimeLegendOrder(points))
    s += (s.empty() ? "" : ", ") + name + " " + std::to_string(counts.at(name));
  return s.empty() ? "none yet" : s;
}

// "100 x 100 = 10000 points", "40 points"
std::string gridText(const SweepGrid& grid) {
  std::string s;
  for (const auto& a : grid.axes()) s += (s.empty() ? "" : " x ") + std::to_string(a.count);
  if (grid.axes().size() > 1) s += " = " + std::to_string(grid.size());
  return s + (grid.size() == 1 ? " point" : " points");
}

std::string mapTitle(const SweepManifest& m) {
  return m.rig_name + " - " + modelTitle(m.model) +
         (m.model == "full" ? " (" + m.engine + ")" : "") + ", N = " + std::to_string(m.metronomes);
}

void writeSweepJson(const OutputDir& dir, const nlohmann::json& j) {
  writeFileAtomically(dir.file("sweep.json"), j.dump(2) + "\n");
}

std::string timingsPath(const OutputDir& dir) {
  return dir.file("timings.csv");
}

// The test hook: METROSYNC_SWEEP_STOP_AFTER=K ends the process like kill -9 right after the K-th
// point of this invocation is written (no sorting, no maps, sweep.json still incomplete).
long stopAfterHook() {
  const char* v = std::getenv("METROSYNC_SWEEP_STOP_AFTER");
  return v && *v ? std::atol(v) : -1;
}

}  // namespace

// ---- sweep
// ---------------------------------------------------------------------------------------

namespace {

// The sweep's stages, top to bottom: plan (the grid and every point's rig, validated before any
// file), resume (what the folder already holds), run (points on threads, rows appended as they
// finish), finish (sorted regimes.csv, maps, sweep.json, the console summary).
struct SweepPlan {
  SweepGrid grid;
  SweepShard shard;
  std::string text;  // the rig's YAML
  Rig base;
  int n = 0;
  long mine = 0;  // how many grid points this shard holds (SweepShard::contains says which)
  SweepManifest manifest;
  std::string path, regimes_path;
  std::vector<size_t> map_axes;   // --map
  std::vector<RandomKey> random;  // --random (with --basin-samples)
  int ranks = 1;                  // MPI processes sharing the points (tools/cli/sweep_mpi.h)
};

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
  if (axes.size() != 2 || !axes[0].values.size() || axes[0].count < 2 || axes[1].count < 2)
    throw UsageError("--boundaries: needs a map over two keys (two --vary of 2 or more values)");
  for (const SweepAxis& a : axes)
    if (a.spec.find(':') == std::string::npos)
      throw UsageError("--boundaries: --vary " + a.key + "=" + a.spec +
                       ": give a range FROM:TO:COUNT (the curves are continuous in both keys)");
  try {
    checkBoundaryKeys(opt.rig_path, opt.sets, axes[0].key, axes[0].values.front(),
                      axes[0].values.back(), axes[1].key, axes[1].values.front(),
                      axes[1].values.back());
  } catch (const UsageError& e) {
    throw UsageError(std::string("--boundaries: ") + e.what());
  }
}

// The fold and Hopf curves over the map's two ranges (boundaryCurves, tools/cli/continue.h).
std::vector<continuation::FoldCurve> mapBoundaries(const SweepOptions& opt, const SweepPlan& plan) {
  const SweepAxis &x = plan.grid.axes()[0], &y = plan.grid.axes()[1];
  return boundaryCurves(opt.rig_path, opt.sets, x.key, x.values.front(), x.values.back(), y.key,
                        y.values.front(), y.values.back());
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
  if (opt.jobs < 0) throw UsageError("--jobs " + std::to_string(opt.jobs) + ": must be >= 1");
  std::vector<SweepAxis> axes;
  for (const auto& v : opt.vary) axes.push_back(parseVary(v));
  SweepPlan plan;
  plan.grid = SweepGrid(std::move(axes), opt.force ? kMaxForcedGridPoints : kMaxGridPoints);
  plan.map_axes = mapAxes(plan.grid, opt.map);
  plan.shard = opt.shard.empty() ? SweepShard{} : parseShard(opt.shard);
  // the rig, its keys, and every grid point's rig: a bad key or value stops here, before any file
  plan.text = sweepRigText(opt);
  const std::optional<Network> net = loadSweepNetwork(plan.text, displayName(opt), opt.sets);
  plan.base = net ? networkSweepRig(*net) : loadRigText(plan.text, displayName(opt), opt.sets);
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

// --resume: the same sweep, and what it already has (this shard's rows only)
RegimesTable resumeTable(const SweepOptions& opt, const SweepPlan& plan, bool& resuming) {
  RegimesTable table;
  resuming = false;
  if (opt.resume) {
    const std::string& path = plan.path;
    if (fs::exists(path + "/sweep.json")) {
      const SweepManifest old = readSweepManifest(path);
      std::string diff = sweepDifference(old, plan.manifest);
      if (diff.empty() && (old.shard.k != plan.shard.k || old.shard.n != plan.shard.n))
        diff = "it is shard " + old.shard.text() + ", not " + plan.shard.text();
      if (!diff.empty())
        throw UsageError("--resume: " + path + " holds another sweep: " + diff +
                         " (resume it with its own command line, or choose another --out)");
      table = readRegimesCsv(plan.regimes_path, plan.grid, plan.n);
      resuming = true;
    } else if (fs::exists(plan.regimes_path)) {
      throw UsageError("--resume: " + path +
                       " has a regimes.csv but no sweep.json: cannot check "
                       "that it is this sweep");
    } else if (!opt.quiet) {
      std::cerr << "metrosync: nothing to resume in " << path << "/: starting the sweep\n";
    }
  }
  for (auto it = table.lines.begin(); it != table.lines.end();) {  // rows of other shards
    if (!plan.shard.contains(it->first)) {
      table.points.erase(it->first);
      it = table.lines.erase(it);
    } else {
      ++it;
    }
  }
  return table;
}

OutputDir openSweepDir(const std::string& path, bool resuming) {
  try {
    OutputDir d(path);
    if (!resuming) removeStaleSweepOutputs(d);
    return d;
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("--out: ") + e.what());
  }
}

// What the run stage leaves: every point of this shard so far, in regimes.csv's text and as values.
struct SweepRun {
  std::map<long, std::string> lines;
  std::map<long, SweepPoint> points;
  long finished_now = 0;
  int jobs = 1;
};

// One point of the plan: its rig loaded here, in the worker, so that no list of the grid's rigs
// is ever held.
std::optional<SweepPoint> runGridPointUntimed(const SweepPlan& plan, const SweepOptions& opt,
                                              long g) {
  std::optional<PointInput> in;
  try {
    in = loadPoint(plan.text, opt, plan.grid, g);
  } catch (const std::exception& e) {
    return unloadablePoint(g, plan.n, e.what());
  }
  if (static_cast<int>(in->rig.metronomes.size()) != plan.n)
    return unloadablePoint(g, plan.n, "--vary changes the number of metronomes here");
  std::optional<SweepPoint> p = runPoint(*in, g, opt.keep == "envelope");
  const long samples = plan.grid.basin().samples;
  if (!p || samples == 0) return p;
  long in_phase = 0;  // failed samples count as not in phase
  for (long k = 0; k < samples; ++k) {
    const auto q = runSweepPointAt(plan.text, opt,
                                   basinSampleOverrides(plan.grid, plan.random, g, k), plan.n, g);
    if (!q) return std::nullopt;  // interrupted
    in_phase += q->regime == "in-phase";
    p->engine_cpu_seconds += q->engine_cpu_seconds;
  }
  p->in_phase_fraction = static_cast<double>(in_phase) / static_cast<double>(samples);
  return p;
}

// ... with its wall and CPU seconds (timings.csv).
std::optional<SweepPoint> runGridPoint(const SweepPlan& plan, const SweepOptions& opt, long g) {
  const Clock::time_point t0 = Clock::now();
  const double cpu0 = threadCpuSeconds();
  std::optional<SweepPoint> p = runGridPointUntimed(plan, opt, g);
  if (p) {
    p->cpu_seconds = threadCpuSeconds() - cpu0;
    p->wall_seconds = secondsSince(t0);
  }
  return p;
}

SweepRun runSweep(const SweepOptions& opt, SweepPlan& plan, const OutputDir& dir,
                  const RegimesTable& table, bool resuming, const SweepScheduler& schedule) {
  SweepRun run{table.lines, table.points};
  writeSweepJson(dir, sweepStatusJson(plan.manifest, plan.mine, run.points, false));
  const bool fresh = table.complete_bytes == 0;
  RegimesAppender regimes(plan.regimes_path, regimesHeader(plan.grid, plan.n), fresh,
                          table.complete_bytes);
  const size_t timing_bytes = resuming ? resumableTimingsBytes(timingsPath(dir)) : 0;
  RegimesAppender timings(timingsPath(dir), timingsHeader(), timing_bytes == 0, timing_bytes);
  run.jobs = opt.jobs > 0 ? opt.jobs : static_cast<int>(std::thread::hardware_concurrency());
  run.jobs = std::max(1, run.jobs);
  Progress progress(!opt.quiet && ::isatty(2), ProgressLog::wanted(opt.quiet), plan.mine,
                    static_cast<long>(run.points.size()));
  std::optional<EnvelopeStore> store;  // --keep envelope
  if (opt.keep == "envelope") {
    std::set<long> done;  // resumed points keep their rows; the others run again
    for (const auto& [g, line] : table.lines) done.insert(g);
    store.emplace(dir.file(kEnvelopeStoreName), plan.n, !resuming, done);
  }
  const long stop_after = stopAfterHook();
  schedule(
      plan.grid.size(), [&](long g) { return plan.shard.contains(g) && !table.lines.count(g); },
      run.jobs, [&](long g) { return runGridPoint(plan, opt, g); },
      [&](const SweepPoint& p) {
        if (store) store->append(p.index, p.kept_rows);  // before its row: a row has its rows
        const std::string line = formatRegimesRow(plan.grid, p);
        regimes.append(line);
        timings.append(formatTimingsRow(p));
        run.lines[p.index] = line;
        run.points[p.index] = p;
        run.points[p.index].kept_rows.clear();
        progress.finished(!p.complete);
        if (++run.finished_now == stop_after) std::_Exit(137);
      },
      [] { return FileSink::stopRequested(); });
  progress.done();
  regimes.close();
  timings.close();
  return run;
}

void printSweepSummary(const SweepPlan& plan, const SweepRun& run, const OutputDir& dir,
                       const std::vector<std::string>& files, long failed, long before,
                       double wall_s) {
  const SweepShard& shard = plan.shard;
  const int n = plan.n;
  std::cout << "sweep of " << plan.base.name << " (" << modelTitle(plan.manifest.model) << ", " << n
            << (n == 1 ? " metronome" : " metronomes") << "): " << gridText(plan.grid)
            << (shard.n > 1
                    ? ", shard " + shard.text() + ": " + std::to_string(plan.mine) + " of them"
                    : "")
            << "; " << run.points.size() << " done (" << run.finished_now << " now, " << before
            << " before), " << failed << " failed\n"
            << "  regimes: " << countsText(run.points) << "\n"
            << "  wall time " << fmt(wall_s, "%.3g") << " s on "
            << (plan.ranks > 1 ? std::to_string(plan.ranks) + " MPI ranks x " : "") << run.jobs
            << (run.jobs == 1 ? " thread" : " threads") << "\n"
            << "files: " << dir.path() << "/ (" << joined(files) << ")\n";
}

int sweepImpl(const SweepOptions& opt, const SweepScheduler& schedule, int ranks) {
  const Clock::time_point t_start = Clock::now();
  SweepPlan plan = planSweep(opt);
  plan.ranks = ranks;
  // the folder's lock before reading what it holds (a folder in use: exit 2, nothing written)
  std::optional<FolderLock> lock;
  if (fs::is_directory(plan.path)) lock.emplace(plan.path, "metrosync sweep");
  bool resuming = false;
  const RegimesTable table = resumeTable(opt, plan, resuming);

  // from here on files are written
  installStopHandlers();
  const OutputDir dir = openSweepDir(plan.path, resuming);
  if (!lock) lock.emplace(plan.path, "metrosync sweep");
  if (!lock->takenOver().empty())
    std::cerr << "metrosync: note: took over the lock of " << plan.path
              << " from an ended process (" << lock->takenOver() << ")\n";
  for (const auto& w : table.warnings) std::cerr << "metrosync: warning: " << w << "\n";
  const SweepRun run = runSweep(opt, plan, dir, table, resuming, schedule);

  const bool interrupted = FileSink::stopRequested();
  const bool complete = static_cast<long>(run.points.size()) == plan.mine;
  writeSortedRegimesCsv(plan.regimes_path, plan.grid, plan.n, run.lines);
  std::vector<std::string> files = {"regimes.csv", "timings.csv"};
  std::vector<continuation::FoldCurve> curves;
  if (opt.boundaries && complete && !interrupted) {
    curves = mapBoundaries(opt, plan);
    writeFileAtomically(dir.file("boundaries.csv"),
                        boundariesCsv(curves, plan.grid.axes()[0].key, plan.grid.axes()[1].key));
    files.push_back("boundaries.csv");
  }
  if (!opt.no_plot)
    for (const auto& f : plotSweepMaps(dir, plan.grid, plan.n, run.points, mapTitle(plan.manifest),
                                       opt.plot_format, curves, plan.map_axes))
      files.push_back(f);
  files.push_back("sweep.json");
  nlohmann::json status = sweepStatusJson(plan.manifest, plan.mine, run.points, complete);
  status["jobs"] = run.jobs;
  if (ranks > 1) status["mpi_ranks"] = ranks;  // tools/cli/sweep_mpi.h
  status["wall_seconds"] = secondsSince(t_start);
  status["points"]["run_now"] = run.finished_now;
  status["interrupted"] = interrupted;
  status["files"] = files;
  if (opt.boundaries) status["boundaries"] = boundariesJson(curves);
  writeSweepJson(dir, status);

  const long failed = status["points"]["failed"].get<long>();
  const long before = static_cast<long>(table.lines.size());
  if (!opt.quiet) printSweepSummary(plan, run, dir, files, failed, before, secondsSince(t_start));
  if (failed > 0)
    std::cerr << "metrosync: warning: " << failed
              << " grid points failed (regime 'failed', the reason in the message column of "
              << plan.regimes_path << ")\n";
  if (interrupted) {
    std::cerr << "metrosync: error: interrupted by a signal with " << run.points.size() << " of "
              << plan.mine << " points done; continue with the same command and --resume\n";
    return kSimulationFailed;
  }
  return kSuccess;
}

// Do two paths name one folder (both existing)?
bool sameFolder(const std::string& a, const std::string& b) {
  std::error_code ec;
  return fs::equivalent(a, b, ec) && !ec;
}

// No source given twice: the same folder under two names, or two folders holding the same shard.
void checkMergeSources(const SweepOptions& opt, const std::vector<SweepShard>& shards) {
  for (size_t i = 0; i < opt.dirs.size(); ++i)
    for (size_t j = i + 1; j < opt.dirs.size(); ++j) {
      if (sameFolder(opt.dirs[i], opt.dirs[j]))
        throw UsageError("merge: " + opt.dirs[j] + " is given twice (also as " + opt.dirs[i] + ")");
      if (shards[i].n > 1 && shards[i].k == shards[j].k && shards[i].n == shards[j].n)
        throw UsageError("merge: shard " + shards[i].text() + " is given twice: " + opt.dirs[i] +
                         " and " + opt.dirs[j]);
    }
}

int mergeImpl(const SweepOptions& opt) {
  if (opt.dirs.empty()) throw UsageError("merge: give the sweep output directories to join");
  // every manifest and every row first: nothing is written unless they all belong together
  std::optional<SweepManifest> ref;
  std::string ref_dir;
  std::map<long, std::string> lines;
  std::map<long, SweepPoint> points;
  std::map<long, std::string> source;
  std::vector<SweepShard> shards;
  for (const auto& d : opt.dirs) {
    const SweepManifest m = readSweepManifest(d);
    shards.push_back(m.shard);
    if (!ref) {
      ref = m;
      ref_dir = d;
    } else if (const std::string diff = sweepDifference(*ref, m); !diff.empty()) {
      throw UsageError("merge: " + d + " is not the same sweep as " + ref_dir + ": " + diff);
    }
    const RegimesTable t = readRegimesCsv(d + "/regimes.csv", ref->grid, ref->metronomes,
                                          "merge leaves the point out");
    for (const auto& w : t.warnings) std::cerr << "metrosync: warning: " << w << "\n";
    for (const auto& [g, line] : t.lines) {
      auto it = lines.find(g);
      if (it != lines.end() && it->second != line)
        throw UsageError("merge: " + source[g] + " and " + d + " disagree on grid point " +
                         std::to_string(g));
      lines[g] = line;
      points[g] = t.points.at(g);
      source.emplace(g, d);
    }
  }
  checkMergeSources(opt, shards);
  SweepManifest merged = *ref;
  merged.merged = true;
  merged.shard = SweepShard{};
  const SweepGrid& grid = merged.grid;
  const int n = merged.metronomes;
  const std::vector<size_t> map_axes = mapAxes(grid, opt.map);

  const std::string path = opt.out.empty() ? defaultOutputDir(merged.rig_name, "merge") : opt.out;
  for (const auto& d : opt.dirs)
    if (sameFolder(path, d))
      throw UsageError("merge: --out " + path + " is one of the sources (" + d +
                       "): merging into it would replace that shard's files; choose another --out");
  std::optional<FolderLock> lock;
  if (fs::is_directory(path)) lock.emplace(path, "metrosync merge");
  OutputDir dir = [&] {
    try {
      OutputDir d(path);
      removeStaleSweepOutputs(d);
      return d;
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("--out: ") + e.what());
    }
  }();
  if (!lock) lock.emplace(path, "metrosync merge");
  writeSortedRegimesCsv(dir.file("regimes.csv"), grid, n, lines);
  std::vector<std::string> files = {"regimes.csv"};
  for (const auto& f :
       plotSweepMaps(dir, grid, n, points, mapTitle(merged), opt.plot_format, {}, map_axes))
    files.push_back(f);
  files.push_back("sweep.json");
  const bool complete = static_cast<long>(points.size()) == grid.size();
  nlohmann::json status = sweepStatusJson(merged, grid.size(), points, complete);
  status["sources"] = opt.dirs;
  status["files"] = files;
  writeSweepJson(dir, status);

  const long missing = grid.size() - static_cast<long>(points.size());
  if (!opt.quiet)
    std::cout << "merged " << opt.dirs.size() << " sweep directories of " << merged.rig_name << " ("
              << modelTitle(merged.model) << "): " << points.size() << " of " << grid.size()
              << " points\n  regimes: " << countsText(points) << "\nfiles: " << dir.path() << "/ ("
              << joined(files) << ")\n";
  if (missing > 0)
    std::cerr << "metrosync: warning: " << missing
              << " grid points are in none of the directories (white in the maps; sweep.json "
                 "says complete: false)\n";
  return kSuccess;
}

}  // namespace

std::string sweepRigText(const SweepOptions& opt) {
  // the same checks as every command: a regular file of bounded size (yaml/rig_loader.h)
  if (opt.rig_text) return *opt.rig_text;
  return opt.rig_path.empty() ? defaultRigYaml() : readRigFile(opt.rig_path);
}

std::pair<std::string, std::string> checkSweepPoint(const std::string& rig_text,
                                                    const SweepOptions& opt,
                                                    const std::vector<std::string>& point, int n,
                                                    const std::string& where) {
  const PointInput in = loadPointRig(rig_text, opt, point, where, "the drawn");
  if (static_cast<int>(in.rig.metronomes.size()) != n)
    throw UsageError(joined(point) + " changes the number of metronomes (at " + where + ")");
  return {in.engine->model(), in.engine->name()};
}

std::optional<SweepPoint> runSweepPointAt(const std::string& rig_text, const SweepOptions& opt,
                                          const std::vector<std::string>& point, int n,
                                          long index) {
  std::optional<PointInput> in;
  try {
    in = loadPointRig(rig_text, opt, point, "point " + std::to_string(index));
  } catch (const std::exception& e) {
    return unloadablePoint(index, n, e.what());
  }
  if (static_cast<int>(in->rig.metronomes.size()) != n)
    return unloadablePoint(index, n, "the point changes the number of metronomes");
  return runPoint(*in, index, false);  // basin samples: no envelope kept
}

namespace {

// sweep's --force, --map, --basin-samples, --random and --seed.
void addSweepMapAndBasinOptions(CLI::App& sweep, SweepOptions& opt) {
  sweep.add_flag("--force", opt.force,
                 "run a grid of more than 10^7 points (without it such a grid is refused)");
  sweep
      .add_option("--map", opt.map,
                  "the two --vary keys the maps draw, across then up (default: the first two); "
                  "every combination of the other keys' values gets its own maps, "
                  "regimes--KEY=VALUE.png, ...")
      ->type_name("KEY1,KEY2");
  sweep
      .add_option("--basin-samples", opt.basin_samples,
                  "with --random: also run S random starts at every point and give the fraction "
                  "that ends in-phase (column in_phase_fraction, map basin.png; docs/basin.md)")
      ->type_name("S")
      ->check(CLI::Range(1L, 1000000L));
  sweep
      .add_option("--random", opt.random,
                  "with --basin-samples: a start key drawn uniformly from FROM to TO (angles on "
                  "the circle), as for `metrosync basin`; repeatable")
      ->type_name("KEY=FROM:TO")
      ->allow_extra_args(false);
  sweep.add_option("--seed", opt.seed, "with --basin-samples: the seed of the draws (default 1)")
      ->type_name("N");
}

}  // namespace

namespace {

// sweep's inputs and how it runs: RIG, --vary, --set, --model, --engine, --jobs, --resume,
// --shard, --out, -q.
void addSweepRunOptions(CLI::App& sweep, SweepOptions& opt) {
  sweep.add_option("RIG", opt.rig_path,
                   "rig file (YAML, SPEC section 1); default: the built-in rig (the paper's "
                   "experiment)");
  sweep
      .add_option(
          "--vary", opt.vary,
          "a key and its values: COUNT values from FROM to TO, both included; ':open' "
          "leaves TO out ([FROM, TO), for angles); ':log' spaces them evenly in log "
          "(0 < FROM <= TO); or the values listed, V1,V2,... "
          "(e.g. platform.friction.mu=0.2,0.3,0.4). Values may use pi: "
          "--vary platform.friction.mu=0:0.8:41, --vary "
          "metronomes.0.start.phi=0:2pi:100:open, --vary platform.friction.mu=0.01:10:31:log. "
          "metronomes.*.KEY sets KEY of every metronome (--vary metronomes.*.nu=0.5:0.8:4). "
          "Repeatable: one axis each, an N-D grid (the first the slowest; the maps draw "
          "two, see --map)")
      ->type_name("KEY=FROM:TO:COUNT[:open][:log]|V1,V2,..")
      ->required()
      ->allow_extra_args(false);
  sweep
      .add_option("--set", opt.sets,
                  "override a rig key for every point, e.g. --set simulation.tau=100; repeatable")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  sweep
      .add_option("--model", opt.model,
                  "slow: the slow flow; full: the full model (default: the --engine's model, "
                  "else slow; full for a network of platforms, docs/networks.md)")
      ->check(CLI::IsMember({"slow", "full"}));
  sweep.add_option("--engine", opt.engine, anyEngineHelp());
  sweep
      .add_option("--jobs", opt.jobs,
                  "worker threads (default: the number of cores); the results do not "
                  "depend on it")
      ->type_name("N")
      ->check(CLI::Range(1, 4096));
  sweep.add_flag("--resume", opt.resume,
                 "continue the sweep in --out DIR: points already in its regimes.csv are "
                 "kept, the others run (the command line must be the same)");
  sweep
      .add_option("--shard", opt.shard,
                  "run only the K-th of N slices of the grid (points with index mod N = "
                  "K-1); join the slices with `metrosync merge`")
      ->type_name("K/N");
  sweep
      .add_option("--out", opt.out,
                  "output directory (default: runs/<rig name>-sweep); metrosync's own output "
                  "files already there are replaced (unless --resume)")
      ->type_name("DIR");
  sweep.add_flag("-q,--quiet", opt.quiet,
                 "no progress bar and no summary (errors and warnings still go to stderr)");
}

// sweep's outputs: the maps' axes and basin samples, --boundaries, --no-plot, --plot-format,
// --keep, and the footer.
void addSweepOutputOptions(CLI::App& sweep, SweepOptions& opt) {
  addSweepMapAndBasinOptions(sweep, opt);
  sweep.add_flag("--boundaries", opt.boundaries,
                 "with --model slow over two ranges: the slow flow's fold and Hopf curves "
                 "(continuation) over the regime map, boundaries.csv");
  sweep.add_flag("--no-plot", opt.no_plot,
                 "draw no maps (regimes.csv, sweep.json and timings.csv only)");
  sweep
      .add_option("--plot-format", opt.plot_format,
                  "format of the maps: png (default), svg or pdf (gnuplot's pngcairo, svg and "
                  "pdfcairo terminals)")
      ->check(CLI::IsMember(plotFormats()))
      ->capture_default_str();
  sweep
      .add_option("--keep", opt.keep,
                  "envelope: keep every point's envelope rows in DIR/envelopes.csv.gz (one "
                  "gzip'd CSV with a point column; docs/sweep-points.md); `metrosync "
                  "sweep-point DIR INDEX` re-runs one point with full outputs")
      ->check(CLI::IsMember({"envelope"}));
  sweep.footer(
      "Files in --out DIR: regimes.csv (one row per grid point, appended as points finish, "
      "sorted by grid index at the end: the varied keys, regime, A_1..A_N, psi_2..psi_N (final, "
      "psi in [0, 2 pi)), r, s (= |Z|/mu: <= 1 a stuck platform), clusters, tau, complete, "
      "index, message), sweep.json (what was "
      "swept, how far it got), timings.csv (wall and CPU seconds per point, and the CPU seconds "
      "inside the engine), regimes.png, "
      "amplitudes.png, phases.png, order.png (N >= 3), drive.png (Coulomb platforms); with more "
      "than two --vary one set of maps per value of the keys not drawn (regimes--KEY=VALUE.png); "
      "with --basin-samples the column in_phase_fraction (after tau) and basin.png.\n"
      "A point whose run fails is recorded with regime 'failed' and the reason; the sweep goes "
      "on. A progress bar with ETA goes to stderr when it is a terminal; otherwise a line at every "
      "10% of a sweep that has run for 5 s. SIGINT/SIGTERM stop the "
      "sweep (the points in flight are not recorded; exit 3): --resume continues it, as it does "
      "after kill -9.\n"
      "Exit codes: 0 success; 2 bad command line or rig (nothing written); 3 interrupted; 1 "
      "anything else.");
}

CLI::App* addMergeCommand(CLI::App& app, SweepOptions& opt) {
  CLI::App* merge =
      app.add_subcommand("merge", "join the regimes.csv of sweep shards into one, with maps");
  merge->add_option("DIR", opt.dirs, "output directories of `sweep --shard K/N` runs")
      ->required()
      ->check(CLI::ExistingDirectory);
  merge->add_option("--out", opt.out, "output directory (default: runs/<rig name>-merge)")
      ->type_name("DIR");
  merge->add_flag("-q,--quiet", opt.quiet, "no summary on stdout");
  merge
      ->add_option("--plot-format", opt.plot_format,
                   "format of the maps: png (default), svg or pdf")
      ->check(CLI::IsMember(plotFormats()))
      ->capture_default_str();
  merge->add_option("--map", opt.map, "the two --vary keys the maps draw (as for sweep)")
      ->type_name("KEY1,KEY2");
  merge->footer(
      "The directories must hold the same sweep (rig, --set, model, grid: their sweep.json "
      "says); points missing from all of them are reported and left white in the maps.\n"
      "Exit codes: 0 success; 2 bad command line or directories that do not belong together "
      "(nothing written); 1 anything else.");
  return merge;
}

}  // namespace

SweepCommands addSweepCommands(CLI::App& app, SweepOptions& opt) {
  SweepCommands c;
  c.sweep = app.add_subcommand(
      "sweep", "a grid of runs over one or more rig keys, in parallel and resumable: a regime map");
  addSweepRunOptions(*c.sweep, opt);
  addSweepOutputOptions(*c.sweep, opt);
  c.merge = addMergeCommand(app, opt);
  return c;
}

int sweepCommand(const SweepOptions& opt) {
  const SweepScheduler threads = [](long size, const std::function<bool(long)>& wanted, int jobs,
                                    const SweepPointRunner& run, const SweepPointSink& finished,
                                    const std::function<bool()>& stop) {
    runSweepPoints(size, wanted, jobs, run, finished, stop);
  };
  return sweepCommand(opt, threads, 1);
}

int sweepCommand(const SweepOptions& opt, const SweepScheduler& schedule, int ranks) {
  try {
    return sweepImpl(opt, schedule, ranks);
  } catch (const SweepInputError& e) {
    throw UsageError(e.what());
  } catch (const FolderLockedError& e) {
    throw UsageError(e.what());
  }
}

SweepPointRunner sweepPointRunner(const SweepOptions& opt) {
  try {
    auto plan = std::make_shared<const SweepPlan>(planSweep(opt));
    return [plan, opt](long g) { return runGridPoint(*plan, opt, g); };
  } catch (const SweepInputError& e) {
    throw UsageError(e.what());
  }
}

int mergeCommand(const SweepOptions& opt) {
  try {
    return mergeImpl(opt);
  } catch (const SweepInputError& e) {
    throw UsageError(e.what());
  } catch (const FolderLockedError& e) {
    throw UsageError(e.what());
  }
}

}  // namespace metrosync::cli
