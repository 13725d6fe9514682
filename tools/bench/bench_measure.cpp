#include "tools/bench/bench_measure.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <thread>

#include "base/number_text.h"
#include "tools/bench/careful_peer.h"
#include "tools/bench/run_method.h"
#include "tools/report/outputs.h"

namespace metrosync::bench {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The peer is stopped after its repeats' budget and this much more (its start, the scene's
// conversion): far above either.
constexpr double kPeerSlackS = 30;

Record baseRecord(const Scene& scene, const Method& m) {
  Record rec;
  rec.scene = scene.name;
  rec.n_metronomes = static_cast<int>(scene.rig.metronomes.size());
  rec.periods = scene.periods;
  rec.method = m;
  return rec;
}

void setCounts(Record& rec, const RunResult& r) {
  rec.steps = r.counts.steps;
  rec.rhs_evals = r.counts.rhs_evals;
  rec.events = r.counts.events;
  rec.ticks = r.ticks;
  rec.stick_slip = r.counts.stick_slip;
  rec.regime = r.regime;
}

void progress(const Record& rec, const BenchOptions& c, bool with_error) {
  if (c.quiet) return;
  // the programs (the careful peer, `metrosync run`) give their own medians, and no envelope
  const bool peer = rec.method.engine == "peer" || rec.method.engine == "run";
  const std::string timing =
      rec.method.engine == "run"
          ? ", wall_seconds " + numberText(rec.wall_median_s, 3) + " s"
          : ", CPU " +
                numberText(peer || std::isnan(rec.cpu_final_median_s) ? rec.cpu_median_s
                                                                      : rec.cpu_final_median_s,
                           3) +
                " s";
  std::cerr << "  " << rec.scene << " " << rec.method.label() << " " << rec.method.setting() << ": "
            << rec.status << (rec.runs ? timing : "")
            << (with_error ? ", final-state error " +
                                 numberText(rec.error.final_state, 2, Notation::Scientific)
                           : "")
            << (with_error && !peer
                    ? ", envelope error " + numberText(rec.error.envelope, 2, Notation::Scientific)
                    : "")
            << ", load " << numberText(rec.load_min, 2, Notation::Fixed) << "-"
            << numberText(rec.load_max, 2, Notation::Fixed) << "\n";
}

void writeEnvelope(const Scene& scene, const Method& m, const RunResult& first,
                   const BenchOptions& c) {
  std::filesystem::create_directories(c.envelopes);
  std::string text = envelopeHeader(static_cast<int>(scene.rig.metronomes.size())) + "\n";
  for (const auto& row : first.envelope) text += formatEnvelopeRow(row) + "\n";
  std::string name = scene.name + "-" + m.engine + "-" + m.integrator + "-" + m.setting();
  std::replace(name.begin(), name.end(), '/', '_');
  writeFileAtomically(c.envelopes + "/" + name + ".csv", text);
}

// A method that is another program timed in its own way (the careful peer, `metrosync run`): one
// call of `repeat` runs, its medians.
Record measureProgram(const Scene& scene, const Method& m, const RunResult* ref,
                      const BenchOptions& c, double budget_s, int repeat, RunResult* keep) {
  Record rec = baseRecord(scene, m);
  rec.load_min = rec.load_max = waitForLoad(c);
  RunResult r;
  int runs = 0;
  if (m.engine == "peer") {
    PeerCall call = runCarefulPeer(scene, m, repeat, budget_s * repeat + kPeerSlackS);
    r = std::move(call.result), runs = call.runs;
  } else {  // each run of `metrosync run` within the budget
    RunCall call = runMetrosyncCommand(scene, m, repeat, budget_s + kPeerSlackS);
    r = std::move(call.result), runs = call.runs;
  }
  setCounts(rec, r);
  if (ref) rec.error = compareRuns(r, *ref);
  if (r.over_budget) {
    rec.status = "over budget";
    rec.note = r.failure;
    rec.wall_median_s = budget_s;
  } else if (!r.complete) {
    rec.status = "failed";
    rec.note = r.failure;
  } else {
    rec.status = "ok";
    rec.runs = runs;
    rec.wall_median_s = rec.wall_final_median_s = r.wall_s;
    rec.cpu_median_s = rec.cpu_final_median_s = r.cpu_s;
    rec.wall_min_s = rec.wall_max_s = kNaN;  // the program reports its median only
    rec.engine_median_s = r.engine_s;
    rec.wall_over_engine = r.wall_over_engine;
  }
  rec.load_max = std::max(rec.load_max, loadAverage1());
  progress(rec, c, ref != nullptr);
  if (keep) *keep = r;
  return rec;
}

// `repeat` runs without samples: the final-state timings, error and counts.
void measureFinalState(const Scene& scene, const Method& m, const RunResult& sampled,
                       const RunResult* ref, const BenchOptions& c, double budget_s, int repeat,
                       Record& rec, std::vector<double>& loads) {
  std::vector<double> walls, cpus;
  for (int k = 0; k < repeat; ++k) {
    loads.push_back(waitForLoad(c));
    const RunResult run = runOnce(scene, m, budget_s, Sampling::FinalState);
    if (!run.complete) break;
    if (k == 0) {
      setCounts(rec, run);
      rec.regime = sampled.regime;
      rec.final_sampled_diff = maxAbsDifference(run.final_state, sampled.final_state);
      if (ref) rec.error.final_state = compareRuns(run, *ref).final_state;
    }
    walls.push_back(run.wall_s);
    cpus.push_back(run.cpu_s);
  }
  rec.wall_final_median_s = median(walls);
  rec.cpu_final_median_s = median(cpus);
  rec.runs = std::min(rec.runs, static_cast<int>(walls.size()));
}

}  // namespace

double waitForLoad(const BenchOptions& c) {
  double load = loadAverage1();
  if (!(c.max_load > 0)) return load;
  const auto t0 = std::chrono::steady_clock::now();
  bool told = false;
  while (load >= c.max_load &&
         std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() <
             c.max_wait_s) {
    if (!told && !c.quiet)
      std::cerr << "  (load " << load << " >= " << c.max_load << ": waiting)\n", told = true;
    std::this_thread::sleep_for(std::chrono::seconds(10));
    load = loadAverage1();
  }
  return load;
}

double maxAbsDifference(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size() || a.empty()) return kNaN;
  double d = 0;
  for (size_t k = 0; k < a.size(); ++k) d = std::max(d, std::abs(a[k] - b[k]));
  return d;
}

Record measure(const Scene& scene, const Method& m, const RunResult* ref, const BenchOptions& c,
               double budget_s, int repeat, bool final_timings, RunResult* keep) {
  if (m.engine == "peer" || m.engine == "run")
    return measureProgram(scene, m, ref, c, budget_s, repeat, keep);
  Record rec = baseRecord(scene, m);
  std::vector<double> walls, cpus, loads;
  loads.push_back(waitForLoad(c));
  RunResult first = runOnce(scene, m, budget_s);
  setCounts(rec, first);
  if (ref) rec.error = compareRuns(first, *ref);
  if (first.over_budget) {
    rec.status = "over budget";
    rec.note = "stopped after " + numberText(first.wall_s, 0, Notation::Fixed) + " s at row " +
               std::to_string(first.envelope.size()) + " of ~" +
               numberText(scene.periods, 0, Notation::Fixed);
    rec.wall_median_s = first.wall_s;
  } else if (!first.complete) {
    rec.status = "failed";
    rec.note = first.failure;
  } else {
    rec.status = "ok";
    walls.push_back(first.wall_s);
    cpus.push_back(first.cpu_s);
    for (int k = 1; k < repeat; ++k) {
      loads.push_back(waitForLoad(c));
      const RunResult again = runOnce(scene, m, budget_s);
      if (!again.complete) break;
      walls.push_back(again.wall_s);
      cpus.push_back(again.cpu_s);
    }
    rec.runs = static_cast<int>(walls.size());
    rec.wall_median_s = median(walls);
    rec.wall_min_s = *std::min_element(walls.begin(), walls.end());
    rec.wall_max_s = *std::max_element(walls.begin(), walls.end());
    rec.cpu_median_s = median(cpus);
    if (final_timings) measureFinalState(scene, m, first, ref, c, budget_s, repeat, rec, loads);
  }
  rec.load_min = *std::min_element(loads.begin(), loads.end());
  rec.load_max = *std::max_element(loads.begin(), loads.end());
  progress(rec, c, ref != nullptr);
  if (!c.envelopes.empty()) writeEnvelope(scene, m, first, c);
  if (keep) *keep = std::move(first);
  return rec;
}

}  // namespace metrosync::bench
