// metrosync_fit_bench: how often `metrosync fit` recovers a rig from rough guesses (issue 27,
// docs/bench/fit.md). Each record is made by the Simbody engine -- an integration independent of
// the direct engine the fit runs -- for two Wittner metronomes on the experiment's board, with
// truths drawn in the paper's ranges (mu-bar in [6.4e-4, 4.6e-3], log-uniform; scaled nu in
// [0.5, 0.7] and J in [2.8, 3.6] per metronome, as in its figures), random start amplitudes and
// phase difference, sampled at 100 Hz with Gaussian noise of 1e-3 rad on both angles. The fit
// frees five keys (mu, both dampings, both impulses), each started at truth x (1 + U(-0.5, 0.5)).
// A record is recovered when every key is identifiable and within 3 standard errors and 5% of
// its truth. Writes the table and the summary (success rate, median time per fit) as markdown.
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
#include "models/scaling.h"
#include "sim/engines/engine.h"
#include "sim/parallel/worker_pool.h"
#include "tools/cli/fit.h"
#include "yaml/rig_loader.h"

namespace {

using namespace metrosync;

constexpr double kNoiseRad = 1e-3;  // a good camera's
constexpr double kSampleS = 0.01;   // 100 Hz
constexpr double kStartOff = 0.5;   // starts within +-50% of the truth
constexpr double kSigmas = 3.0;     // recovered: within 3 standard errors ...
constexpr double kRelative = 0.05;  // ... and 5%
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

struct Outcome {
  int index = 0;  // 0-based record number
  Truth truth;
  double start[5] = {};
  FitReport report;
  double rms_from_truth = 0.0;  // the same fit, --local from the truth: its optimum's rms
  double wall_s = 0.0, cpu_s = 0.0;
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

// The CPU time of the calling thread (records run on several threads at once).
double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
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
     << numberText(o.cpu_s, 1, Notation::Fixed) << " | " << (o.recovered ? "yes" : "**no**")
     << " |\n";
  return os.str();
}

std::string report(const std::vector<Outcome>& all, unsigned seed, const Settings& set,
                   const std::string& command) {
  int ok = 0, honest = 0;
  std::vector<double> cpu, wall;
  std::string rows;
  for (std::size_t i = 0; i < all.size(); ++i) {
    ok += all[i].recovered;
    // a failure the verdict owns up to: converged false
    honest += all[i].recovered || !all[i].report.outcome.converged;
    cpu.push_back(all[i].cpu_s);
    wall.push_back(all[i].wall_s);
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
     << "| median CPU time per fit | " << numberText(median(cpu), 1, Notation::Fixed) << " s |\n"
     << "| median wall time per fit | " << numberText(median(wall), 1, Notation::Fixed)
     << " s (a machine shared with other jobs) |\n\n"
     << "Columns: mu-bar of the truth; each start's offset from the truth in % (mu, damping 1, "
     << "damping 2, impulse 1, impulse 2); each fitted key's error in its standard errors "
     << "(n/i: not identifiable); the rms residual (rad); the rms of the optimum the same fit "
     << "reaches with --local from the truth (for comparison; not timed); the verdict; distinct "
     << "optima found; model runs; CPU seconds.\n\n"
     << "| # | mu-bar | start off (%) | error (std. errors) | rms | rms from the truth | "
        "converged | optima | runs | CPU s | recovered |\n"
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n"
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
  std::string command = "metrosync_fit_bench";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  std::ofstream(out) << report(all, seed, set, command);
  if (!csv.empty()) std::ofstream(csv) << recordsCsv(all);
  if (keep.empty()) std::filesystem::remove_all(set.dir);
  return 0;
}
