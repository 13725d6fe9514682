// One point of a sweep or a basin (sim/analysis/sweep.h): its rig or network ready to run, and its
// run down to one regimes.csv row. No loader in here: the caller builds the point (the CLI from
// the rig's text, --set and the point's values; a program from its own rig).
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "models/network.h"
#include "models/rig.h"
#include "models/scaling.h"
#include "sim/analysis/sweep.h"
#include "sim/engines/engine.h"

namespace metrosync {

// One grid point, ready to run.
struct PointInput {
  Rig rig;                         // a network's: its sweep rig (scales, metronome count)
  ScaledParams scaled;             // computeScaled(rig) (a single rig's)
  const Engine* engine = nullptr;  // the engine it runs on
  std::optional<Network> net;      // a network of platforms
};

// What the caller adds to a point's run.
struct PointHooks {
  // a stop request (a signal): the run stops at its next row and the point is not recorded
  std::function<bool()> stop;
  // tests: a point made to fail with this message (nullopt: runs as it is)
  std::function<std::optional<std::string>(long)> fault;
  bool keep_envelope = false;  // the point's envelope rows into SweepPoint::kept_rows
};

// Runs point g: its row (regime, final A, psi, r, s, clusters, tau, complete, message, the
// engine's CPU seconds), or nullopt when a stop request interrupted it; a failed run is a row of
// regime "failed" with the reason.
std::optional<SweepPoint> runPoint(const PointInput& in, long g, const PointHooks& hooks = {});

// A point that could not even be loaded: failed, with the loader's message (n metronomes).
SweepPoint unloadablePoint(long g, int n, const std::string& why);

}  // namespace metrosync
