// What `metrosync run` costs against its engine (issues 23 and 36): the built binary run as a
// user runs it (`metrosync run SCENE --quiet --no-plot`, files written; the scene kDefaultRig,
// "default", is the built-in default rig, `metrosync run --no-plot` with no rig file), K times per
// scene and variant (e.g. --set simulation.sample=100), after one run that warms the page cache and
// is not counted. Per run: summary.json's wall_seconds (the integration with its recording) and
// engine_seconds (the integrator and its events), and the whole process's wall and CPU time
// measured from outside. Then the same engine, integrator and accuracy as summary.json names, on
// the same rig and overrides, K times in the bench's own process with recording off (the
// bench's final-state runs): "engine alone". Both ratios, wall_seconds / engine_seconds (the
// median of each run's) and wall_seconds / engine alone (the medians'), have the target
// kRunRatioTarget.
#pragma once

#include <string>
#include <vector>

#include "tools/bench/bench_measure.h"
#include "tools/bench/speed_inputs.h"
#include "tools/bench/speed_targets.h"

namespace metrosync::bench {

// Issues 23 and 36: `run` costs what the engine costs, within 15%.
constexpr double kRunRatioTarget = kRunOverEngineTarget;

struct RunCostOptions {
  std::string metrosync = "build/metrosync";  // the binary
  std::vector<std::string> scenes;            // rig files
  // each variant is a list of KEY=VALUE overrides given as --set ("" = the rig as it is) and of
  // env:NAME=VALUE settings of the run's environment (e.g. env:METROSYNC_RECORDING_THREAD=never)
  std::vector<std::string> variants = {"", "simulation.sample=100"};
  int repeat = 5;
  std::string tmp;  // where the runs write their files ("" = the system's temporary directory)
};

struct RunCostRow {
  std::string scene, variant;  // the rig file as given; the --set overrides, "" for none
  int runs = 0;
  double wall_seconds = 0.0, engine_seconds = 0.0;  // medians of summary.json's
  // median over the runs of each run's wall_seconds / engine_seconds (one run's two numbers share
  // its preemptions; the medians of the two may come from different runs)
  double ratio = 0.0;
  double ratio_min = 0.0, ratio_max = 0.0;  // over the runs
  // the engine in the bench's process, recording off: its wall median, and wall_seconds over it
  double engine_alone_s = 0.0, over_alone = 0.0;
  std::string engine;  // engine:integrator:accuracy, as summary.json names them
  // runs whose split is impossible (engine_seconds <= 0 or > wall_seconds): counted, shown, and
  // left out of the medians of engine_seconds and of the ratio
  int inconsistent = 0;
  double process_wall_s = 0.0, process_cpu_s = 0.0;  // medians, measured from outside
  double load_min = 0.0, load_max = 0.0;
  std::string command;  // one run's command line (its --out left out)
  std::string failure;  // "" when every run succeeded
};

// Runs every scene with every variant; progress on stderr unless c.quiet.
std::vector<RunCostRow> measureRunCost(const RunCostOptions& o, const BenchOptions& c);

// run.csv, and the Markdown table with the verdict against kRunRatioTarget.
std::string runCostCsv(const std::vector<RunCostRow>& rows);
std::string runCostMarkdown(const std::vector<RunCostRow>& rows, const std::string& command);

}  // namespace metrosync::bench
