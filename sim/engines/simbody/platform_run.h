// The one run loop of the Simbody engine (docs/architecture.md), for a single rig (a network of
// one) and for a network of platforms alike: the system of models/simbody/platform_system.h,
// Simbody's integrator, thin witnesses, the shared event resolver (sim/events/resolver.h), the
// grazing guard, and samples on the shared schedule (sim/events/sample_schedule.h). What it
// records and how its report reads are the caller's: a RunRecorder takes the samples and the
// event rows (its one recorder: simbody_engine.cpp, a single rig's rows and a network's states).
#pragma once

#include <Simbody.h>

#include <string>
#include <vector>

#include "sim/record/run_report.h"

namespace metrosync {

class PlatformSystem;

// What a run records. Pendulums are numbered as the network's metronomes (models/network.h:
// global, file order, locked ones included); -1 is a platform.
class RunRecorder {
 public:
  virtual ~RunRecorder() = default;
  // simulation.sample (<= 0: the schedule's default)
  virtual double sampleInterval() const = 0;
  // a scheduled sample at t (the state is the integrator's interpolant there), with which kinds
  // are due: a row (simulation.sample) and an envelope sample (64 per period, kept on the schedule
  // though the envelope now comes from stretchTo: the report times bound Simbody's steps, and
  // every run is stepped as it was, a network of one exactly as the single rig).
  virtual void sample(const SimTK::State& s, double t, bool row, bool envelope) = 0;
  // The trajectory's smooth stretches, as Simbody interpolates them (cubic Hermite between two
  // states and their derivatives, Integrator's interpolant): restartAt(s) where one starts (the
  // first state, and the state after every event's impulses), stretchTo(s) at the end of every
  // step kept (s realized to accelerations), each ending the stretch since the last.
  virtual void restartAt(const SimTK::State& s) {}
  virtual void stretchTo(const SimTK::State& s) {}
  // event rows and the event record (sim/record/run_report.h RunSink)
  virtual bool wantsEventRecords() const { return false; }
  virtual void eventRow(const char* kind, const SimTK::State& s) {}
  virtual void snapshotBefore(const SimTK::State& s) {}
  virtual void recordEvent(const char* kind, int metronome, const SimTK::State& s) {}
  // after every step the integrator took (t in seconds): RunSink::poll
  virtual void poll(double t) {}
  // the run's last state (at exactly the requested end when it completed)
  virtual void finish(const SimTK::State& s) = 0;
  // the failure message: `why` at t (seconds)
  virtual std::string failureText(double t, const std::string& why) const = 0;
};

struct PlatformRunResult {
  bool complete = true;
  std::string failure;
  RunCounts counts;       // escapements per metronome (network numbering); events: live windows
  long forced_stops = 0;  // slips stopped at the end of the step they ended in (not windows)
  long event_rows = 0;    // event rows ("tick", "stick", "slip") the resolvers wrote
  EnergyLedger ledger;
  double t_end = 0.0;  // where the run stopped
  double wall_seconds = 0.0, engine_seconds = 0.0;
};

// Runs the system to its network's sim.t_end_s with `integrator` (a Simbody integrator name) at
// the network's sim.accuracy. time_scale_s: 1/omega0, the fast period / 2 pi (steps, witnesses).
PlatformRunResult runPlatforms(PlatformSystem& ps, const std::string& integrator,
                               double time_scale_s, RunRecorder& recorder);

}  // namespace metrosync
