// metrosync_fit_bench: how often `metrosync fit` recovers a rig from rough guesses (issue 27,
// docs/bench/fit.md). Each record is made by the Simbody engine -- an integration independent of
// the direct engine the fit runs -- for two Wittner metronomes on the experiment's board, with
// truths drawn in the paper's ranges (mu-bar in [6.4e-4, 4.6e-3], log-uniform; scaled nu in
// [0.5, 0.7] and J in [2.8, 3.6] per metronome, as in its figures), random start amplitudes and
// phase difference, sampled at 100 Hz with Gaussian noise of 1e-3 rad on both angles. The fit
// frees five keys (mu, both dampings, both impulses), each started at truth x (1 + U(-0.5, 0.5)).
// A record is recovered when every key is identifiable and within 3 standard errors and 5% of
// its truth. Writes the table and the summary (success rate, median time per fit) as markdown,
// and what a fit costs against runs of the same rig, measured on each record's truth in the same
// bench run (CPU of the record's thread, wall; medians of kRepeats):
//   one `run`      `metrosync run RECORD.yaml --no-plot --quiet` in this process (its files in the
//                  scratch directory, synced; no process start-up), the records one after another
//                  after the fits (CPU of the process: the sync runs on a worker thread)
//   the engine     the direct engine on the record's rig with `run`'s recording (rows at the
//                  default sampling, envelope, events) into memory: no files
//   a model run    what the fit runs per evaluation: the model to the record's end, rows at the
//                  data's spacing, event records (sim/analysis/fit/model_samples.h)
//   a derivatives  the exact derivatives of the samples in the five keys from that run (its
//   run            variational equations, sim/analysis/fit/model_jacobian.h): k model runs
//
//   metrosync_fit_bench [--records N] [--seed S] [--duration SECONDS] [--data-engine
//   simbody|direct] [--only I] [--jobs N] [--out FILE.md] [--keep DIR] [--csv FILE.csv]
//
// Records run on --jobs threads (each its own scratch files and random stream: the table does not
// depend on N); the CPU seconds are each fit's own thread's.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <random>
#include <sstream>

#include "base/constants.h"
#include "base/number_text.h"
#include "base/thread_cpu_time.h"
#include "models/scaling.h"
#include "sim/analysis/fit/data_file.h"
#include "sim/analysis/fit/fit_observations.h"
#include "sim/analysis/fit/model_jacobian.h"
#include "sim/analysis/fit/model_samples.h"
#include "sim/engines/engine.h"
#include "sim/parallel/worker_pool.h"
#include "tools/cli/commands.h"
#include "tools/cli/fit.h"
#include "yaml/rig_loader.h"
#include "yaml/rig_writer.h"

namespace {

using namespace metrosync;

constexpr double kNoiseRad = 1e-3;  // a good camera's
constexpr double kSampleS = 0.01;   // 100 Hz
constexpr double kStartOff = 0.5;   // starts within +-50% of the truth
constexpr double kSigmas = 3.0;     // recovered: within 3 standard errors ...
constexpr double kRelative = 0.05;  // ... and 5%
constexpr int kRepeats = 5;         // timings of a run: the median of this many
const char* kKeys[5] = {"platform.friction.mu", "metronomes.0.pendulum.damping",
                        "metronomes.1.pendulum.damping", "metronomes.0.escapement.impulse",
                        "metronomes.1.escapement.impulse"};

struct Truth {
  double value[5];  // in kKeys order
  double amplitude[2], psi;
};

// printf's %+.<decimals>f: fixed, with its sign always written (a relative error's table cell)
std::string signedText(double v, int decimals) {
  return (std::signbit(v) ? "" : "+") + numberText(v, decimals, Notation::Fixed);
}

// The experiment's rig (yaml/rigs/experiment.yaml) with the truth's keys; metronome 2 starts
// psi behind metronome 1 on its small-angle cycle.
std::string rigYaml(const Truth& t, double duration_s) {
  const double w = 1.0 / 0.04789;  // small-angle frequency (rad/s) of the experiment's pendulum
  std::ostringstream os;
  os.precision(17);
  os << "units: physical\nname: bench\ngravity: 9.81\nplatform:\n  mass: 0.1432\n"
     << "  friction: {law: coulomb, mu: " << t.value[0] << "}\nmetronomes:\n";
  for (int i = 0; i < 2; ++i) {
    const double ph = i == 0 ? 0.0 : t.psi, a = t.amplitude[i];
    os << "  - name: " << (i ? "B" : "A") << "\n    box_mass: 0.0602\n"
       << "    pendulum: {mass: 0.0226, length: 0.0225, damping: " << t.value[1 + i] << "}\n"
       << "    escapement: {angle: 0.244, impulse: " << t.value[3 + i] << "}\n"
       << "    start: {angle: " << a * std::cos(ph) << ", rate: " << -a * w * std::sin(ph) << "}\n";
  }
  os << "simulation:\n  duration: " << duration_s << "\n";
  return os.str();
}

// Truths in the paper's ranges, in physical units through the experiment rig's scaling.
Truth drawTruth(std::mt19937& gen) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Truth t{};
  t.value[0] = 6.4e-4 * std::pow(4.6e-3 / 6.4e-4, u(gen));
  t.amplitude[0] = 0.5 + 0.35 * u(gen);
  t.amplitude[1] = 0.5 + 0.35 * u(gen);
  t.psi = kTwoPi * u(gen);
  const Rig rig = loadRigText(rigYaml({{1e-3, 0.02, 0.02, 1e-5, 1e-5}, {0.7, 0.7}, 0}, 1), "b");
  const ScaledParams sp = computeScaled(rig);
  const MetronomeSpec& m = rig.metronomes[0];
  const double inertia = m.inertia_kgm2, w0 = 1 / sp.time_scale_s;
  for (int i = 0; i < 2; ++i) {
    const double nu = 0.5 + 0.2 * u(gen), J = 2.8 + 0.8 * u(gen);
    t.value[1 + i] = sp.epsilon * nu * inertia * w0 / (m.length_m * m.length_m);
    t.value[3 + i] = sp.epsilon * std::sqrt(sp.epsilon) * J * inertia * w0;
  }
  return t;
}

// The Simbody engine's angles every 10 ms with N(0, kNoiseRad) noise, as CSV; empty when the
// run fails.
std::string measured(const std::string& rig_yaml, const std::string& engine, std::mt19937& gen) {
  Rig rig = loadRigText(rig_yaml, "bench.yaml");
  rig.sim.sample_s = kSampleS;
  MemorySink sink;
  if (!selectEngine(engine, "full", "").run(rig, sink).complete) return "";
  std::normal_distribution<double> noise(0.0, kNoiseRad);
  std::ostringstream os;
  os.precision(10);
  os << "t,theta_1,theta_2\n";
  for (const std::vector<double>& row : sink.trajectory)
    os << row[0] << "," << row[3] + noise(gen) << "," << row[5] + noise(gen) << "\n";
  return os.str();
}

// What runs of the record's rig cost, seconds (medians of kRepeats).
struct Costs {
  double run_cpu = 0, run_wall = 0;        // one `run` command
  double engine_cpu = 0, engine_wall = 0;  // the engine's run with `run`'s recording
  double model_cpu = 0;                    // one model run of the fit
  double derivatives_cpu = 0;              // its derivatives in the five keys
};

struct Outcome {
  int index = 0;  // 0-based record number
  Truth truth;
  double start[5] = {};
  FitReport report;
  double rms_from_truth = 0.0;  // the same fit, --local from the truth: its optimum's rms
  double wall_s = 0.0, cpu_s = 0.0;
  Costs costs;
  bool recovered = false;
  std::string error;
};

bool recovered(const Outcome& o) {
  const FitOutcome& r = o.report.outcome;
  for (int k = 0; k < 5; ++k) {
    if (!r.values[k]) return false;
    const double err = std::abs(*r.values[k] - o.truth.value[k]);
    if (!(err < kSigmas * *r.std_errors[k] && err < kRelative * o.truth.value[k])) return false;
  }
  return true;
}

struct Settings {
  double duration_s = 60.0;
  std::string engine = "simbody";  // the engine that makes the records
  std::string dir;                 // scratch directory for rig.yaml and data.csv
};

double wallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double median(std::vector<double> v);

double processCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

// The median CPU (of the thread, or of the process) and wall seconds of kRepeats calls of f.
template <class F>
std::pair<double, double> timed(F&& f, double (*cpu_seconds)() = threadCpuSeconds) {
  std::vector<double> cpu, wall;
  for (int r = 0; r < kRepeats; ++r) {
    const double c0 = cpu_seconds(), w0 = wallSeconds();
    f();
    cpu.push_back(cpu_seconds() - c0);
    wall.push_back(wallSeconds() - w0);
  }
  return {median(cpu), median(wall)};
}

// The costs of the record's rig at its truth (the header says which runs).
Costs measureCosts(const std::string& rig_yaml, const std::string& data_csv, const Truth& truth) {
  Costs c;
  const Engine& direct = selectEngine("direct", "full", "");
  const Rig rig = loadRigText(rig_yaml, "bench.yaml");
  std::tie(c.engine_cpu, c.engine_wall) = timed([&] {
    MemorySink sink;
    direct.run(rig, sink);
  });
  const MeasuredData data = parseDataText(data_csv, "bench.csv", 2);
  const FitData fd = fitData(
      data, false, {rig.metronomes[0].theta_c_rad, rig.metronomes[1].theta_c_rad}, kNoiseRad);
  FitProblem p;
  p.data = &data;
  p.engine = &direct;
  for (int k = 0; k < 5; ++k) {
    FreeParameter f;
    f.name = kKeys[k];
    f.keys = {kKeys[k]};
    f.start = f.scale = truth.value[k];
    p.free.push_back(f);
  }
  p.rig = [&](const std::vector<double>& v) {
    std::vector<std::string> sets;
    for (int k = 0; k < 5; ++k) sets.push_back(std::string(kKeys[k]) + "=" + exactNumberText(v[k]));
    return loadRigText(rig_yaml, "bench.yaml", sets);
  };
  const std::vector<double> values(truth.value, truth.value + 5);
  const int n = static_cast<int>(fd.observations.size());
  const double t_end = fd.observations.back().t_s, row_dt = modelRowInterval(data.t_s, rig);
  c.model_cpu = timed([&] { ModelTrajectory(direct, rig, t_end, row_dt); }).first;
  const ModelTrajectory run(direct, rig, t_end, row_dt);
  c.derivatives_cpu =
      timed([&] { modelJacobian(p, values, run, fd, n, std::vector<bool>(5, true)); }).first;
  return c;
}

// One `run` of record o's rig (its file in the scratch directory), into o.costs.
void timeRunCommand(const Settings& set, Outcome& o) {
  cli::Options run;
  run.rig_path = set.dir + "/record" + std::to_string(o.index + 1) + ".yaml";
  run.out = set.dir + "/run" + std::to_string(o.index + 1);
  run.quiet = run.no_plot = true;
  std::tie(o.costs.run_cpu, o.costs.run_wall) =
      timed([&] { cli::runCommand(run); }, processCpuSeconds);
  std::filesystem::remove_all(run.out);
}

// Record `index` (0-based): its rig and data in the scratch directory under its own names.
Outcome fitRecord(const Truth& truth, const Settings& set, int index, std::mt19937& gen) {
  Outcome o;
  o.index = index;
  o.truth = truth;
  const std::string rig = rigYaml(truth, set.duration_s), data = measured(rig, set.engine, gen);
  const std::string stem = set.dir + "/record" + std::to_string(index + 1);
  std::ofstream(stem + ".yaml") << rig;
  std::ofstream(stem + ".csv") << data;
  cli::FitOptions opt;
  opt.rig_path = stem + ".yaml";
  opt.data_path = stem + ".csv";
  std::uniform_real_distribution<double> off(-kStartOff, kStartOff);
  for (int k = 0; k < 5; ++k) {
    o.start[k] = truth.value[k] * (1 + off(gen));
    opt.free.push_back(kKeys[k]);
    opt.sets.push_back(std::string(kKeys[k]) + "=" + numberText(o.start[k], 17));
  }
  std::ofstream cmd(stem + ".command");  // the same fit from the command line
  cmd << "metrosync fit " << stem << ".yaml " << stem << ".csv";
  for (std::size_t k = 0; k < opt.free.size(); ++k)
    cmd << " --free " << opt.free[k] << " --set " << opt.sets[k];
  cmd << "\n";
  if (data.empty()) return o.error = "the " + set.engine + " run failed", o;
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = threadCpuSeconds();
  try {
    o.report = cli::runFit(opt);
  } catch (const std::exception& e) {
    o.error = e.what();
  }
  o.cpu_s = threadCpuSeconds() - c0;
  o.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  o.recovered = o.error.empty() && recovered(o);
  o.costs = measureCosts(rig, data, truth);
  // the optimum nearest the truth, for comparison: is the one found as good?
  opt.local = true;
  opt.starts = 1;
  opt.sets.clear();
  for (int k = 0; k < 5; ++k)
    opt.sets.push_back(std::string(kKeys[k]) + "=" + numberText(truth.value[k], 17));
  try {
    o.rms_from_truth = cli::runFit(opt).outcome.rms;
  } catch (const std::exception&) {
    o.rms_from_truth = NAN;
  }
  return o;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty()      ? 0.0
         : v.size() % 2 ? v[v.size() / 2]
                        : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// one table row: the truth, how far off each start was, the fit's error in standard errors
std::string row(int i, const Outcome& o) {
  std::ostringstream os;
  os << "| " << i + 1 << " | " << numberText(o.truth.value[0], 2, Notation::Scientific) << " |";
  for (int k = 0; k < 5; ++k) os << " " << signedText(100 * (o.start[k] / o.truth.value[k] - 1), 0);
  os << " |";
  const FitOutcome& r = o.report.outcome;
  for (int k = 0; k < 5 && o.error.empty(); ++k)
    os << " "
       << (r.values[k] ? signedText((*r.values[k] - o.truth.value[k]) / *r.std_errors[k], 1)
                       : std::string("n/i"));
  if (!o.error.empty()) os << " " << o.error;
  os << " | " << numberText(r.rms, 4) << " | " << numberText(o.rms_from_truth, 4) << " | "
     << (r.converged ? "yes" : "no") << " | " << r.optima.size() << " | " << r.evaluations << " | "
     << r.jacobians << " | " << numberText(o.cpu_s, 2, Notation::Fixed) << " | "
     << (o.costs.run_cpu > 0 ? numberText(o.cpu_s / o.costs.run_cpu, 0, Notation::Fixed) : "-")
     << " | " << (o.recovered ? "yes" : "**no**") << " |\n";
  return os.str();
}

// The medians of the costs: per fit, and against one `run` and one model run of the same rig.
std::string costLines(const std::vector<Outcome>& all) {
  std::vector<double> cpu, wall, runs, derivatives, k, equivalent, run_cpu, run_wall, ratio_cpu,
      ratio_wall, engine_cpu, engine_wall, engine_ratio;
  for (const Outcome& o : all) {
    const FitOutcome& r = o.report.outcome;
    cpu.push_back(o.cpu_s);
    wall.push_back(o.wall_s);
    runs.push_back(r.evaluations);
    derivatives.push_back(r.jacobians);
    k.push_back(o.costs.derivatives_cpu / o.costs.model_cpu);
    equivalent.push_back(r.evaluations + k.back() * r.jacobians);
    run_cpu.push_back(o.costs.run_cpu);
    run_wall.push_back(o.costs.run_wall);
    ratio_cpu.push_back(o.cpu_s / o.costs.run_cpu);
    ratio_wall.push_back(o.wall_s / o.costs.run_wall);
    engine_cpu.push_back(o.costs.engine_cpu);
    engine_wall.push_back(o.costs.engine_wall);
    engine_ratio.push_back(o.cpu_s / o.costs.engine_cpu);
  }
  const auto fixed = [](double v, int d) { return numberText(v, d, Notation::Fixed); };
  std::ostringstream os;
  os << "| median CPU time per fit | " << fixed(median(cpu), 2) << " s |\n"
     << "| median wall time per fit | " << fixed(median(wall), 2)
     << " s (2 records at once, on a machine shared with other jobs) |\n"
     << "| median model runs per fit | " << fixed(median(runs), 0) << ", and "
     << fixed(median(derivatives), 0)
     << " runs of its derivatives (one costs k = " << fixed(median(k), 2)
     << " model runs: " << fixed(median(equivalent), 0)
     << " model runs in all; a window's run is shorter than the record's) |\n"
     << "| one `run` of the same rig (`run RIG --no-plot --quiet` in process, files synced) | "
     << "CPU " << fixed(1e3 * median(run_cpu), 1) << " ms, wall "
     << fixed(1e3 * median(run_wall), 1) << " ms |\n"
     << "| a fit against one `run` of its rig | " << fixed(median(ratio_cpu), 0) << "x in CPU, "
     << fixed(median(ratio_wall), 0) << "x in wall |\n"
     << "| the engine alone (`run`'s recording into memory, no files) | CPU "
     << fixed(1e3 * median(engine_cpu), 1) << " ms, wall " << fixed(1e3 * median(engine_wall), 1)
     << " ms: a fit is " << fixed(median(engine_ratio), 0) << "x its CPU |\n";
  return os.str();
}

std::string report(const std::vector<Outcome>& all, unsigned seed, const Settings& set,
                   const std::string& command) {
  int ok = 0, honest = 0;
  std::string rows;
  for (std::size_t i = 0; i < all.size(); ++i) {
    ok += all[i].recovered;
    // a failure the verdict owns up to: converged false
    honest += all[i].recovered || !all[i].report.outcome.converged;
    rows += row(all[i].index, all[i]);
  }
  std::ostringstream os;
  os << "# Fit recovery from rough guesses (issue 27)\n\n"
     << "Made by `" << command << "` (tools/bench/fit_recovery.cpp says how).\n\n"
     << all.size() << " records of " << set.duration_s << " s at 100 Hz, made by the " << set.engine
     << " engine "
     << "with 1e-3 rad of noise on both angles (seed " << seed << "); five keys free, each "
     << "started within +-50% of its truth.\n\n"
     << "| | |\n| --- | --- |\n"
     << "| recovered (every key within 3 standard errors and 5%) | " << ok << " of " << all.size()
     << " (" << numberText(100.0 * ok / all.size(), 0, Notation::Fixed) << "%) |\n"
     << "| failures reported as not converged | " << honest - ok << " of " << all.size() - ok
     << " |\n"
     << costLines(all) << "\n"
     << "Columns: mu-bar of the truth; each start's offset from the truth in % (mu, damping 1, "
     << "damping 2, impulse 1, impulse 2); each fitted key's error in its standard errors "
     << "(n/i: not identifiable); the rms residual (rad); the rms of the optimum the same fit "
     << "reaches with --local from the truth (for comparison; not timed); the verdict; distinct "
     << "optima found; model runs; runs of the model's derivatives; CPU seconds; the fit's CPU "
     << "against one `run` of its rig.\n\n"
     << "| # | mu-bar | start off (%) | error (std. errors) | rms | rms from the truth | "
        "converged | optima | runs | derivatives | CPU s | x run | recovered |\n"
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n"
     << rows;
  return os.str();
}

// One line per record for the speed bench (tools/bench/fit_cost.h): its timings and verdict.
std::string recordsCsv(const std::vector<Outcome>& all) {
  std::ostringstream os;
  os << "record,wall_s,cpu_s,model_runs,converged,recovered,error\n";
  for (const Outcome& o : all)
    os << o.index + 1 << "," << numberText(o.wall_s, 6) << "," << numberText(o.cpu_s, 6) << ","
       << o.report.outcome.evaluations << "," << (o.report.outcome.converged ? 1 : 0) << ","
       << (o.recovered ? 1 : 0) << ",\"" << o.error.substr(0, o.error.find_first_of("\"\n"))
       << "\"\n";
  return os.str();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("metrosync_fit_bench: fit recovery from starts +-50% off (docs/bench/fit.md)");
  int records = 50, only = 0, jobs = 1;
  unsigned seed = 1;
  Settings set;
  std::string out = "docs/bench/fit.md", keep, csv;
  app.add_option("--records", records, "synthetic records (default 50)");
  app.add_option("--seed", seed, "random seed (default 1)");
  app.add_option("--duration", set.duration_s, "seconds per record (default 60)");
  app.add_option("--data-engine", set.engine, "the engine that makes the records (default simbody)")
      ->check(CLI::IsMember({"simbody", "direct"}));
  app.add_option("--only", only, "run record I alone (1-based; its draws do not depend on others)");
  app.add_option("--jobs", jobs, "records fitted at once, each on its own thread (default 1)")
      ->check(CLI::Range(1, 64));
  app.add_option("--out", out, "markdown file to write (default docs/bench/fit.md)");
  app.add_option(
      "--keep", keep,
      "keep each record's rig, data and fit command (recordI.yaml, .csv, .command) in DIR");
  app.add_option("--csv", csv, "also write each record's timings and verdict to FILE.csv");
  CLI11_PARSE(app, argc, argv);
  set.dir =
      !keep.empty()
          ? keep
          : (std::filesystem::temp_directory_path() /
             ("metrosync-fit-bench-" + std::to_string(seed) + "-" + std::to_string(::getpid())))
                .string();
  std::filesystem::create_directories(set.dir);
  const int first = only > 0 ? only - 1 : 0, count = only > 0 ? 1 : records;
  std::vector<Outcome> all(count);
  std::mutex print;
  parallelFor(count, jobs, [&](long k) {
    const int i = first + static_cast<int>(k);
    std::mt19937 gen(seed * 100003u + i);  // each record its own stream
    all[k] = fitRecord(drawTruth(gen), set, i, gen);
    const std::lock_guard<std::mutex> lock(print);
    std::cerr << row(i, all[k]);
  });
  for (Outcome& o : all) timeRunCommand(set, o);  // alone, after the fits
  std::string command = "metrosync_fit_bench";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  std::ofstream(out) << report(all, seed, set, command);
  if (!csv.empty()) std::ofstream(csv) << recordsCsv(all);
  if (keep.empty()) std::filesystem::remove_all(set.dir);
  return 0;
}
