// The direct engine's options (sim/engines/direct/direct_engine.h, direct_run.h).
#pragma once

#include "sim/events/storm_guard.h"

namespace metrosync {

struct DirectOptions {
  // The storm rule's limits (sim/events/storm_guard.h): more than `storm_events` events with time
  // advancing by less than `storm_window` fast periods (2 pi / omega0) ends the run, incomplete.
  long storm_events = StormGuard::kMaxEvents;
  double storm_window = StormGuard::kWindowPeriods;
  // Run a single board as any network is run: the general equations (a solve for the holding
  // force, no rate), steps of at most kMaxStepPeriods of a period, its states on the sample grid
  // (direct_model.h). For tests that hold the two against each other; commands never set it.
  bool general_equations = false;
};

}  // namespace metrosync
