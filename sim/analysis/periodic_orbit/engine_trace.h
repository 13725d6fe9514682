// A stretch of the full model run by the direct engine from a given state, seen as the engine's
// event windows: when each happened, the states just before and just after it and the platform
// modes, and which pendulums ticked. The engine's event core decides everything here (which
// events, in what order, at what time); sim/analysis/periodic_orbit only linearizes around it.
// Built from the public interface alone: runDirectModel and the event records of a RunSink
// (sim/record/run_report.h), the records of one window sharing its time.
#pragma once

#include <string>
#include <vector>

#include "models/rig.h"
#include "sim/analysis/periodic_orbit/scaled_model.h"
#include "sim/record/run_report.h"

namespace metrosync::orbit {

struct EngineWindow {
  double t = 0.0;     // time, in the model's units (scaled; seconds for PhysicalModel)
  Vec before, after;  // states (d x 1), likewise
  PlatformMode mode_before = PlatformMode::Stuck, mode_after = PlatformMode::Stuck;
  std::vector<int> ticked;       // swinging-pendulum indices, ascending
  bool platform_switch = false;  // a stick/slip record in the window
};

struct EngineTrace {
  bool complete = true;
  std::string failure;                            // the engine's, when !complete
  PlatformMode start_mode = PlatformMode::Stuck;  // after the engine's settling at t = 0
  std::vector<EngineWindow> windows;              // t > 0, in order
  long steps = 0;
};

// A sink that takes nothing: the run's final state (RunReport::final_trajectory_row) is all a
// caller wants; the engine then takes no samples at all.
struct FinalStateSink : RunSink {
  bool wantsEventRows() const override { return false; }
  bool wantsTrajectory() const override { return false; }
  bool wantsEnvelope() const override { return false; }
};

// Runs `rig` (its parameters; start and duration replaced) from the scaled state z0 for t_end
// (scaled time) with the engine at `accuracy`.
EngineTrace traceFrom(const Rig& rig, const ScaledModel& model, const Vec& z0, double t_end,
                      double accuracy);

// A run's event records (RunSink::eventRecord's, in order) as its windows at t > 0 and its mode at
// the start, whose xdot is v0: in scaled units, or in SI for a physical rig's records.
EngineTrace traceOfRecords(const ScaledModel& model, const std::vector<EventRecord>& records,
                           double v0);
EngineTrace traceOfRecords(const PhysicalModel& model, const std::vector<EventRecord>& records,
                           double v0);

}  // namespace metrosync::orbit
