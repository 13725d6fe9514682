// What a benchmark run is of (a Scene), how it runs (a Method) and what it gives (a RunResult):
// the values that tools/bench/bench_run.h runs and compares and the peers
// (tools/bench/careful_peer.h, peer_scene.h) fill in.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "models/rig.h"
#include "models/scaling.h"
#include "sim/record/envelope.h"
#include "sim/record/run_report.h"

namespace metrosync::bench {

// A scene: a rig and what the error measures need from it.
struct Scene {
  std::string name;  // short name for tables and file names (the rig file's stem)
  std::string path;  // the rig file ("" for a rig built in code)
  Rig rig;
  ScaledParams scaled;
  double periods = 0.0;  // fast periods (2 pi / omega0) in the run
};

// What runs: an engine, one of its integrators and its accuracy knob.
struct Method {
  std::string engine;             // simbody | direct | siconos | odeint | peer
  std::string integrator;         // the engine's integrator name (siconos: moreau-jean)
  double accuracy = 0.0;          // relative local error target (simbody, direct)
  double steps_per_period = 0.0;  // siconos: h = fast period / steps_per_period
  std::string label() const { return engine + ":" + integrator; }
  std::string setting() const;  // "1e-08" or "h=T/256"
};

struct RunResult {
  Method method;
  bool complete = true;
  std::string failure;
  bool over_budget = false;  // stopped by the benchmark's time budget
  double wall_s = 0.0;       // the whole call: building the system and running it
  double cpu_s = 0.0;        // process CPU time over the same interval
  // `metrosync run` (tools/bench/run_method.h): the median of summary.json's engine_seconds and
  // of each run's wall_seconds / engine_seconds; NaN for the other methods
  double engine_s = std::numeric_limits<double>::quiet_NaN();
  double wall_over_engine = std::numeric_limits<double>::quiet_NaN();
  RunCounts counts;
  long ticks = 0;  // sum of counts.escapements
  std::vector<EnvelopeRow> envelope;
  std::vector<double> final_state;  // scaled: xdot, theta_1, thetadot_1, ..., theta_N, thetadot_N
  std::string regime;
};

// A run that did not happen or did not finish: `why`, no regime.
inline RunResult failedRun(const Method& m, const std::string& why) {
  RunResult r;
  r.method = m;
  r.complete = false;
  r.failure = why;
  r.regime = "unknown";
  return r;
}

}  // namespace metrosync::bench
