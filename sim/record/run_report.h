// What a run of either model returns, and the sink it streams its rows into. The engines
// (sim/simbody/ for the full model, models/slow_flow for the slow flow) know nothing about files;
// sim/outputs turns a sink into the SPEC section 3 files.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact/platform_mode.h"
#include "models/rig.h"
#include "models/scaling.h"
#include "sim/record/envelope.h"

namespace metrosync {

// Energy bookkeeping of a full-model run (physical units, joules): what the system has now
// against what it had, what the escapement put in and what damping and friction took out.
struct EnergyLedger {
  double initial_J = 0.0;        // kinetic + potential at the start
  double final_J = 0.0;          // kinetic + potential at the end
  double escapement_in_J = 0.0;  // sum over ticks of the kinetic-energy jump
  double damping_out_J = 0.0;    // integral of nu-bar L^2 thetadot^2 over all pivots
  double friction_out_J = 0.0;   // integral of |F xdot| (Coulomb slip, viscous)
  // (final - initial) - (in - out): zero up to integration error
  double residual_J() const {
    return (final_J - initial_J) - (escapement_in_J - damping_out_J - friction_out_J);
  }
  // residual relative to the largest energy flow
  double relativeResidual() const;
};

struct RunCounts {
  long steps = 0;                 // integrator steps taken
  long rhs_evals = 0;             // right-hand-side (realize Acceleration) evaluations
  std::vector<long> escapements;  // (N x 1) ticks per metronome
  long stick_slip = 0;            // platform stick <-> slip transitions
  long slip_reversals = 0;        // slip+ <-> slip- without sticking in between
  long events = 0;                // event windows of any kind, and plastic stops
};

struct RunReport {
  std::string model;       // "full" or "slow"
  std::string engine;      // "simbody", "direct", "slowflow"
  std::string integrator;  // the integrator used
  double accuracy = 0.0;
  bool complete = true;       // false when the run stopped early
  std::string failure;        // why it stopped, with the time (empty when complete)
  double wall_seconds = 0.0;  // the run: integration, events and recording (sample capture)
  // the integrator and its events alone: wall_seconds less the time spent taking samples and
  // handing rows to the sink (docs/outputs.md)
  double engine_seconds = 0.0;
  // after the run, the time its files took to be written: the rows' text is made on writer
  // threads while the run goes on (tools/report/deferred_rows.h), and this is what was left when
  // it ended (0 for runs without files)
  double write_seconds = 0.0;
  RunCounts counts;
  bool has_ledger = false;
  EnergyLedger ledger;
  EnvelopeRow final_row;  // last envelope row (tau, A, psi)
  // full model: state at the end, in the rig's units: t, x, xdot, theta_i, thetadot_i, platform
  std::vector<double> final_trajectory_row;
  // A run of a network of platforms (models/network.h; its states go to RunSink::stateSample):
  // counts.escapements in the network's global numbering (locked ones stay 0), the ledger's
  // damping_out_J with the ground and coupling dampers, and
  double t_end = 0.0;               // the requested end exactly when complete, else the stop
  std::vector<double> final_state;  // the state at t_end, in the layout of network::Layout
  double fast_period_s = 0.0;       // 2 pi / omega0 of the network's first swinging pendulum
};

// The one sink of every run, receiving what the run produces as it goes (implementations must not
// keep the whole run in memory): a single rig's rows in the rig's units (trajectory, envelope,
// event rows and records), and a network's state at every sample (stateSample). A run calls what
// its model has and the sink wants: a network of two or more platforms has no rows in a single
// rig's format, so its run calls stateSample only; a single rig's run calls the rows, and when the
// sink wantsStates() also stateSample (both engines: the state as a network of one's, at every row
// sample and at the end). What the sink wants never chooses the model.
struct RunSink {
  virtual ~RunSink() = default;
  // t, x, xdot, theta_1, thetadot_1, ..., theta_N, thetadot_N, platform (0, 1, -1) in the rig's
  // units (physical: SI; scaled: scaled variables). Full model only.
  virtual void trajectoryRow(const std::vector<double>& row) {}
  virtual void envelopeRow(const EnvelopeRow& row) {}
  // Full model: one call per event, with the state just after it in the trajectory format.
  // kind: "tick" (escapement), "stick", "slip" (platform mode after a switch).
  virtual void eventRow(const char* kind, const std::vector<double>& row) {}
  // false: eventRow() ignores its rows, and an engine need not build them (asked once, at the
  // start of a run)
  virtual bool wantsEventRows() const { return true; }
  // false: trajectoryRow() / envelopeRow() ignore their rows, and an engine need not take the
  // samples they come from (asked once, at the start of a run). The run's last state is reported
  // in RunReport::final_trajectory_row either way; without the envelope, RunReport::final_row
  // is empty. A benchmark that measures the integrator alone says false to both.
  virtual bool wantsTrajectory() const { return true; }
  virtual bool wantsEnvelope() const { return true; }
  // Full model: the event record (events.csv), when wantsEventRecords(): one call per tick of
  // each metronome and per platform switch, with the states just before and just after it in
  // the trajectory format. metronome: 0-based rig index; -1 for the platform ("stick", "slip").
  virtual bool wantsEventRecords() const { return false; }
  virtual void eventRecord(const char* kind, int metronome, const std::vector<double>& before,
                           const std::vector<double>& after) {}
  // Full model, a network of platforms (docs/networks.md): the state at every sample time
  // (simulation.sample, default period/20) strictly before the run's end, then its final state (at
  // exactly the requested end when the run completed). y in the layout of network::Layout
  // (models/network_equations.h: x_p, xdot_p, ..., theta_j, ..., thetadot_j, ..., three ledger
  // quadratures), x_p, xdot_p absolute; modes: each platform's contact mode (Stuck for every
  // non-Coulomb contact). false: an engine need not call stateSample (asked once, at the start).
  virtual bool wantsStates() const { return false; }
  virtual void stateSample(double t, const std::vector<double>& y,
                           const std::vector<PlatformMode>& modes) {}
  // Where a run may make this sink's rows: on its own thread (Never), or on a recording thread
  // of its own that calls the row methods above from there (never from two threads at once)
  // while it integrates on, always or only when the run is long enough to pay for the thread
  // (WhenLong: the engine judges). The report's fields come back on the caller's thread. A
  // recording thread is for a run that has a core to itself (the `run` command), not for one of
  // many running in parallel (a sweep's points). Asked once.
  enum class RecordingThread { Never, WhenLong, Always };
  virtual RecordingThread recordingThread() const { return RecordingThread::Never; }
  // Called by a run that started a recording thread, before its first row: every row comes from
  // that thread, which may then also write the rows' text itself (FileSink: no writer threads of
  // its own beside it; on two cores a third and a fourth busy thread would take the run's core).
  virtual void recordingThreadStarted() {}
  // Called by an engine that can take many steps between two rows (Simbody, whose grazing guard
  // redoes steps smaller and smaller) after each of its steps, t in the unit of the rows' t (a
  // network's: seconds). A sink may throw from it to stop the run, as from a row (FileSink: after
  // a stop request, tools/report/outputs.h).
  virtual void poll(double t) {}
};

// A sink of states only (a network's verdict, the animation's track): no single rig's rows.
struct StateSink : RunSink {
  bool wantsTrajectory() const override { return false; }
  bool wantsEnvelope() const override { return false; }
  bool wantsEventRows() const override { return false; }
  bool wantsStates() const override { return true; }
  void stateSample(double t, const std::vector<double>& y,
                   const std::vector<PlatformMode>& modes) override = 0;
};

struct EventRecord {
  std::string kind;
  int metronome = -1;
  std::vector<double> before, after;
};

// A sink that keeps everything in memory: for tests and small comparisons.
struct MemorySink : RunSink {
  // with keep_states: every stateSample too (a network's run)
  bool keep_states = false;
  struct State {
    double t;
    std::vector<double> y;
    std::vector<PlatformMode> modes;
  };
  std::vector<State> states;
  std::vector<std::vector<double>> trajectory;
  std::vector<EnvelopeRow> envelope;
  std::vector<std::pair<std::string, std::vector<double>>> events;
  std::vector<EventRecord> records;
  void trajectoryRow(const std::vector<double>& row) override { trajectory.push_back(row); }
  void envelopeRow(const EnvelopeRow& row) override { envelope.push_back(row); }
  void eventRow(const char* kind, const std::vector<double>& row) override {
    events.emplace_back(kind, row);
  }
  bool wantsEventRecords() const override { return true; }
  void eventRecord(const char* kind, int metronome, const std::vector<double>& before,
                   const std::vector<double>& after) override {
    records.push_back({kind, metronome, before, after});
  }
  bool wantsStates() const override { return keep_states; }
  void stateSample(double t, const std::vector<double>& y,
                   const std::vector<PlatformMode>& modes) override {
    states.push_back({t, y, modes});
  }
};

// Thrown by a sink at the first row after a stop request (FileSink, a sweep's point). A
// std::runtime_error, so that an engine that turns exceptions into a failed report (complete =
// false) stops cleanly; the caller catches it too, for engines that let it through.
struct RunInterrupted : std::runtime_error {
  RunInterrupted(double t_, const std::string& why) : std::runtime_error(why), t(t_) {}
  double t;  // when, in the rig's time unit
};

// Fails a run: the engine stops, reports what it has, and the command exits with code 3.
struct SimulationFailure {
  double t = 0.0;
  std::string why;
};

}  // namespace metrosync
