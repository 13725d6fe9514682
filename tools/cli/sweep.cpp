// `metrosync sweep` (tools/cli/sweep.h): the stages, top to bottom -- plan (sweep_plan.h), resume
// (sweep_folder.h), run (points on the pool's threads, rows appended as they finish: this file),
// finish (sorted regimes.csv, maps, sweep.json, the console summary: this file).
#include "tools/cli/sweep.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <set>

#include "base/number_text.h"
#include "sim/analysis/sweep.h"
#include "tools/cli/commands.h"
#include "tools/cli/fault_hooks.h"
#include "tools/cli/sweep_folder.h"
#include "tools/cli/sweep_plan.h"
#include "tools/cli/sweep_point_run.h"
#include "tools/cli/sweep_progress.h"
#include "tools/cli/sweep_summary.h"
#include "tools/report/envelope_store.h"
#include "tools/report/folder_lock.h"
#include "tools/report/outputs.h"
#include "tools/report/progress_log.h"
#include "tools/report/sweep_files.h"
#include "tools/report/sweep_maps.h"

namespace metrosync::cli {

namespace {

namespace fs = std::filesystem;

std::string timingsPath(const OutputDir& dir) {
  return dir.file("timings.csv");
}

// What the run stage leaves: every point of this shard so far, in regimes.csv's text and as values.
// What the run stage leaves in memory: counts only, whatever the number of points (the rows are
// in regimes.csv, appended as they finish).
struct SweepRun {
  SweepTally tally;  // every point of this shard so far
  long finished_now = 0;
  int jobs = 1;
};

// What --resume found: the points done (a bit per grid point, and one more while reading: the
// rows themselves stay on disk), their tally, and where regimes.csv's whole lines end.
struct Resumed {
  std::vector<bool> done;  // empty: nothing resumed
  SweepTally tally;
  RegimesScan scan;  // complete_bytes and warnings
  bool isDone(long g) const { return !done.empty() && done[static_cast<std::size_t>(g)]; }
};

// --resume: regimes.csv read row by row (the first row of an index wins; rows of other shards and,
// with --keep envelope, points without their whole envelope are not done: they run again).
Resumed resumeSweep(const SweepOptions& opt, const SweepPlan& plan, bool& resuming) {
  Resumed r;
  resuming = checkResumable(opt, plan);
  if (!resuming) return r;
  const auto size = static_cast<std::size_t>(plan.grid.size());
  r.done.assign(size, false);
  std::vector<bool> seen(size, false);
  std::optional<std::set<long>> stored;
  if (opt.keep == "envelope") stored = storedEnvelopePoints(plan.path + "/" + kEnvelopeStoreName);
  long without_envelope = 0;
  r.scan = scanRegimesCsv(plan.regimes_path, plan.grid, plan.n, "the point runs again",
                          [&](const SweepPoint& p, const std::string&) {
                            const auto g = static_cast<std::size_t>(p.index);
                            if (seen[g]) return false;
                            seen[g] = true;
                            if (!plan.shard.contains(p.index)) return true;
                            if (stored && !stored->count(p.index)) {
                              ++without_envelope;
                              return true;
                            }
                            r.done[g] = true;
                            r.tally.add(p);
                            return true;
                          });
  if (without_envelope > 0)
    r.scan.warnings.push_back(std::to_string(without_envelope) +
                              " points of regimes.csv have no whole envelope in " + plan.path +
                              "/" + kEnvelopeStoreName + " (damaged or cut): they run again");
  return r;
}

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
  const SweepClock::time_point t0 = SweepClock::now();
  const double cpu0 = threadCpuSeconds();
  std::optional<SweepPoint> p = runGridPointUntimed(plan, opt, g);
  if (p) {
    p->cpu_seconds = threadCpuSeconds() - cpu0;
    p->wall_seconds = secondsSince(t0);
  }
  return p;
}

SweepRun runSweep(const SweepOptions& opt, SweepPlan& plan, const OutputDir& dir,
                  const Resumed& before, bool resuming, const SweepScheduler& schedule) {
  const RegimesScan& table = before.scan;
  SweepRun run{before.tally};
  writeSweepJson(dir, statusJson(plan.manifest, plan.mine, run.tally, false));
  const bool fresh = table.complete_bytes == 0;
  RegimesAppender regimes(plan.regimes_path, regimesHeader(plan.grid, plan.n), fresh,
                          table.complete_bytes);
  const size_t timing_bytes = resuming ? resumableTimingsBytes(timingsPath(dir)) : 0;
  RegimesAppender timings(timingsPath(dir), timingsHeader(), timing_bytes == 0, timing_bytes);
  SweepProgress progress(!opt.quiet && ::isatty(2), ProgressLog::wanted(opt.quiet), plan.mine,
                         run.tally.done);
  std::optional<EnvelopeStore> store;  // --keep envelope
  if (opt.keep == "envelope")          // resumed points keep their rows; the others run again
    store.emplace(dir.file(kEnvelopeStoreName), plan.n, !resuming,
                  [&](long g) { return before.isDone(g); });
  auto wanted = [&](long g) { return plan.shard.contains(g) && !before.isDone(g); };
  run.jobs = schedule(
      plan.grid.size(), wanted, opt.jobs, [&](long g) { return runGridPoint(plan, opt, g); },
      [&](const SweepPoint& p) {
        if (store) store->append(p.index, p.kept_rows);  // before its row: a row has its rows
        const std::string line = formatRegimesRow(plan.grid, p);
        regimes.append(line);
        timings.append(formatTimingsRow(p));
        run.tally.add(p);
        progress.finished(!p.complete);
        ++run.finished_now;
        if (faultHooks().after_row) faultHooks().after_row(run.finished_now);
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
            << "; " << run.tally.done << " done (" << run.finished_now << " now, " << before
            << " before), " << failed << " failed\n"
            << "  regimes: " << countsText(run.tally) << "\n"
            << "  wall time " << numberText(wall_s, 3) << " s on "
            << (plan.ranks > 1 ? std::to_string(plan.ranks) + " MPI ranks x " : "") << run.jobs
            << (run.jobs == 1 ? " thread" : " threads") << "\n"
            << "files: " << dir.path() << "/ (" << joined(files) << ")\n";
}

// --boundaries: a curve that could not be followed (or all of them) is said on stderr; the map is
// written all the same (exit 0), sweep.json has the same in `boundaries` / `boundaries_error`.
void warnAboutBoundaries(const std::vector<continuation::FoldCurve>& curves,
                         const std::string& error) {
  if (!error.empty())
    std::cerr << "metrosync: warning: --boundaries: no curves (" << error
              << "); the map is written without them\n";
  for (size_t i = 0; i < curves.size(); ++i)
    if (!curves[i].failure.empty())
      std::cerr << "metrosync: warning: --boundaries: the " << toString(curves[i].kind) << " curve "
                << i << " through (" << curves[i].seed_p1 << ", " << curves[i].seed_p2
                << ") could not be followed: " << curves[i].failure << "\n";
}

// The finish: regimes.csv sorted (in bounded passes), the maps from it, sweep.json; returns
// sweep.json's status.
nlohmann::json finishSweep(const SweepOptions& opt, const SweepPlan& plan, const SweepRun& run,
                           const OutputDir& dir, bool interrupted, int ranks) {
  const bool complete = run.tally.done == plan.mine;
  sortRegimesCsv(plan.regimes_path, plan.grid, plan.n,
                 [&](long g) { return plan.shard.contains(g); });
  std::vector<std::string> files = {"regimes.csv", "timings.csv"};
  std::vector<continuation::FoldCurve> curves;
  std::string boundaries_error;  // the curves failed as a whole: the map is written without them
  if (opt.boundaries && complete && !interrupted) {
    try {
      curves = mapBoundaries(opt, plan);
    } catch (const std::exception& e) {
      boundaries_error = e.what();
    }
    writeFileAtomically(dir.file("boundaries.csv"),
                        boundariesCsv(curves, plan.grid.axes()[0].key, plan.grid.axes()[1].key));
    files.push_back("boundaries.csv");
  }
  if (!opt.no_plot && plan.grid.size() <= kMaxMapCells) {
    // the maps' points read back from the sorted regimes.csv, one at a time
    const SweepPointSource points = [&](const std::function<void(const SweepPoint&)>& visit,
                                        const std::function<bool(const std::string&)>& wanted) {
      forEachRegimesRow(plan.regimes_path, plan.grid, plan.n, visit, wanted);
    };
    for (const auto& f : plotSweepMaps(dir, plan.grid, plan.n, points, mapTitle(plan.manifest),
                                       opt.plot_format, curves, plan.map_axes))
      files.push_back(f);
  }
  files.push_back("sweep.json");
  nlohmann::json status = statusJson(plan.manifest, plan.mine, run.tally, complete);
  status["jobs"] = run.jobs;
  if (ranks > 1) status["mpi_ranks"] = ranks;  // tools/cli/sweep_mpi.h
  status["points"]["run_now"] = run.finished_now;
  status["interrupted"] = interrupted;
  status["files"] = files;
  if (opt.boundaries) status["boundaries"] = boundariesJson(curves);
  if (!boundaries_error.empty()) status["boundaries_error"] = boundaries_error;
  warnAboutBoundaries(curves, boundaries_error);
  return status;
}

int sweepImpl(const SweepOptions& opt, const SweepScheduler& schedule, int ranks) {
  const SweepClock::time_point t_start = SweepClock::now();
  SweepPlan plan = planSweep(opt);
  plan.ranks = ranks;
  // the folder's lock before reading what it holds (a folder in use: exit 2, nothing written)
  std::optional<FolderLock> lock;
  if (fs::is_directory(plan.path)) lock.emplace(plan.path, "metrosync sweep");
  bool resuming = false;
  const Resumed before = resumeSweep(opt, plan, resuming);

  // from here on files are written
  installStopHandlers();
  const OutputDir dir = openSweepDir(plan.path, resuming);
  if (!lock) lock.emplace(plan.path, "metrosync sweep");
  if (!lock->takenOver().empty())
    std::cerr << "metrosync: note: took over the lock of " << plan.path
              << " from an ended process (" << lock->takenOver() << ")\n";
  for (const auto& w : before.scan.warnings) std::cerr << "metrosync: warning: " << w << "\n";
  const SweepRun run = runSweep(opt, plan, dir, before, resuming, schedule);

  const bool interrupted = FileSink::stopRequested();
  nlohmann::json status = finishSweep(opt, plan, run, dir, interrupted, ranks);
  status["wall_seconds"] = secondsSince(t_start);
  writeSweepJson(dir, status);
  const long failed = run.tally.failed;
  if (!opt.quiet)
    printSweepSummary(plan, run, dir, status["files"].get<std::vector<std::string>>(), failed,
                      before.tally.done, secondsSince(t_start));
  if (failed > 0)
    std::cerr << "metrosync: warning: " << failed
              << " grid points failed (regime 'failed', the reason in the message column of "
              << plan.regimes_path << ")\n";
  if (interrupted) {
    std::cerr << "metrosync: error: interrupted by a signal with " << run.tally.done << " of "
              << plan.mine << " points done; continue with the same command and --resume\n";
    return kSimulationFailed;
  }
  return kSuccess;
}

}  // namespace

int sweepCommand(const SweepOptions& opt) {
  const SweepScheduler threads = [](long size, const std::function<bool(long)>& wanted, int jobs,
                                    const SweepPointRunner& run, const SweepPointSink& finished,
                                    const std::function<bool()>& stop) {
    return runSweepPoints(size, wanted, jobs, run, finished, stop);
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

}  // namespace metrosync::cli
