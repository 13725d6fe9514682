// What a benchmark run is of (a Scene), how it runs (a Method) and what it gives (a RunResult):
// the values that tools/bench/bench_run.h runs and compares and the peers
// (tools/bench/careful_peer.h, peer_scene.h) fill in.
#pragma once

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
  RunCounts counts;
  long ticks = 0;  // sum of counts.escapements
  std::vector<EnvelopeRow> envelope;
  std::vector<double> final_state;  // scaled: xdot, theta_1, thetadot_1, ..., theta_N, thetadot_N
  std::string regime;
};

}  // namespace metrosync::bench
