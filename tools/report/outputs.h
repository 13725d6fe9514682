// The output files of a command (SPEC section 3), written whole or not at all: every file goes to
// a hidden temporary name in the output directory (".NAME.<pid>.part") and is renamed to NAME when
// complete, so an interrupted run never leaves a truncated file that looks complete. Long runs
// stream their rows to the temporary file as they go (flushed about once a second): memory does
// not grow with the length of a run.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/rig.h"
#include "sim/analysis/regime.h"
#include "sim/record/atomic_file.h"
#include "sim/record/envelope.h"
#include "sim/record/run_report.h"
#include "tools/report/deferred_rows.h"
#include "tools/report/output_dir.h"

namespace metrosync {

class NetworkFiles;
struct Network;

// Keeps at most about `max_rows` of a stream of envelope rows for plotting: when the buffer holds
// 2 max_rows rows every other one is dropped and the stride doubles. The last row is always kept.
class EnvelopeDecimator {
 public:
  explicit EnvelopeDecimator(size_t max_rows = 4000) : max_rows_(max_rows < 2 ? 2 : max_rows) {}
  void add(const EnvelopeRow& row);
  // the kept rows in tau order, ending with the last row seen
  std::vector<EnvelopeRow> rows() const;
  size_t stride() const { return stride_; }

 private:
  size_t max_rows_;
  size_t stride_ = 1;
  long seen_ = 0;
  std::vector<EnvelopeRow> kept_;
  bool have_last_ = false;
  EnvelopeRow last_;
};

// Where and what a model's sink writes.
struct RunFilesOptions {
  int n_metronomes = 0;
  double tau_end = 0.0;    // end of the run in slow time: the regime window is its last 10%
  bool trajectory = true;  // trajectory.csv (full model only)
  std::string trajectory_name = "trajectory.csv";
  std::string envelope_name = "envelope.csv";
  bool events = false;  // events.csv, with the trajectory (full model only)
  std::string events_name = "events.csv";
  // physical rigs: envelope.csv and events.csv get a last column t_s, the row's time in seconds
  // (trajectory.csv's t is in seconds already: the rig's units)
  bool seconds = false;
  size_t max_plot_rows = 4000;
  // to report an interruption "at t = ..." in the rig's time unit: t = tau / epsilon * time_unit
  double epsilon = 1.0;
  double time_unit = 1.0;  // physical rigs: seconds per unit of scaled time; scaled rigs: 1
  // the platform for the `uncoupled` rule when no trajectory row comes (the slow flow):
  // RegimeWindow::setEnvelopePlatform; unset: only the full model's rows tell
  bool envelope_platform = false;
  double x_unit = 1.0;  // trajectory x per unit of scaled x (physical rigs: x_scale_m)
  FrictionLaw law;      // scaled
  // the run may make the rows on a recording thread of its own (RunSink::recordingThread):
  // a run that has the machine to itself (`metrosync run`), not a sweep's points
  RunSink::RecordingThread recording_thread = RunSink::RecordingThread::Never;
  // every file's text written on the thread that makes the rows, no writer threads, whatever
  // the run does (a bench's variant, METROSYNC_RECORDING_THREAD=inline: docs/outputs.md)
  bool text_on_rows_thread = false;
};

// trajectory.csv's header: t,x,xdot,theta_1,thetadot_1,...,theta_N,thetadot_N,platform.
std::string trajectoryHeader(int n);

// events.csv's header: t,tau,kind,who, then x,xdot,theta_i,thetadot_i,platform with _before
// and _after, then t_s when `seconds` (docs/outputs.md).
std::string eventsHeader(int n, bool seconds);

// The one file writer, the RunSink of a command: a single rig's rows stream into trajectory.csv,
// envelope.csv (and events.csv) in `dir`, keeping what the summary and plots need (the regime
// window, a decimated copy of the envelope) in O(N) memory; a network's states into the network's
// files, in its own columns (its part NetworkFiles, tools/report/network_files.h). A stop request
// (requestStop(), e.g. from a SIGINT handler) makes the next row throw RunInterrupted (once), so
// that the engine stops and reports what it has.
class FileSink : public RunSink {
 public:
  FileSink(const OutputDir& dir, const RunFilesOptions& opt);
  // A network of platforms' files (docs/networks.md): its states, no single rig's rows.
  FileSink(const OutputDir& dir, const Network& net);
  ~FileSink() override;
  // No file: the same rows checked and judged, handed only to the tap (the Python module's
  // results in memory without out=, tools/report/run_columns.h).
  explicit FileSink(const RunFilesOptions& opt);
  // Every trajectory row, envelope row and event record also goes to `tap` (not owned; nullptr:
  // none) once this sink has taken it: the rows in memory beside the files.
  void setTap(RunSink* tap) { tap_ = tap; }

  void trajectoryRow(const std::vector<double>& row) override;
  void envelopeRow(const EnvelopeRow& row) override;
  bool wantsEventRecords() const override { return opt_.trajectory && opt_.events; }
  void eventRecord(const char* kind, int metronome, const std::vector<double>& before,
                   const std::vector<double>& after) override;
  // stick/slip events tell the regime window what the platform does between trajectory rows
  void eventRow(const char* kind, const std::vector<double>& row) override;
  bool wantsTrajectory() const override { return !network_; }
  bool wantsEnvelope() const override { return !network_; }
  bool wantsEventRows() const override { return !network_; }
  bool wantsStates() const override { return network_ != nullptr; }
  RecordingThread recordingThread() const override {
    return network_ ? RecordingThread::Never : opt_.recording_thread;
  }
  // the recording thread writes the files' text too (DeferredRows::writeOnCallersThread)
  void recordingThreadStarted() override { textOnRowsThread(); }
  void stateSample(double t, const std::vector<double>& y,
                   const std::vector<PlatformMode>& modes) override;
  // between rows: a stop request stops the run there (RunInterrupted, once)
  void poll(double t) override { checkStop(t); }
  // a network's files: its verdict for summary.json and its rows for the plots (nullptr for a
  // single rig)
  const NetworkFiles* network() const { return network_.get(); }

  // Writes the rows still queued for the writer threads (their text is made off the run's thread:
  // tools/report/deferred_rows.h), then renames every file written to its final name. Called
  // after the run whether it completed or not (a failed run keeps its rows, marked incomplete in
  // summary.json). Returns the seconds spent waiting for the writers (summary.json's
  // write_seconds).
  double commit();

  long trajectoryRows() const { return trajectory_rows_; }
  long envelopeRows() const { return envelope_rows_; }
  long eventRecords() const { return event_rows_; }
  // Called with every event record as it is written (an analysis on the events: section 3A).
  using EventObserver =
      std::function<void(const char* kind, int metronome, const std::vector<double>& before,
                         const std::vector<double>& after)>;
  void setEventObserver(EventObserver f) { observer_ = std::move(f); }
  // Called with every envelope row's tau (progress of the run, tools/report/progress_log.h).
  void setProgress(std::function<void(double tau)> f) { progress_ = std::move(f); }
  const RegimeWindow& regimeWindow() const { return window_; }
  std::vector<EnvelopeRow> plotRows() const { return plot_.rows(); }
  // final names of the files this sink writes (none without a folder)
  std::vector<std::string> fileNames() const;

  // async-signal-safe; process-wide
  static void requestStop();
  static bool stopRequested();
  static void clearStopRequest();

 private:
  void checkStop(double t);
  DeferredRows::Format eventFormat() const;
  DeferredRows::Format envelopeFormat() const;
  void textOnRowsThread();

  RunFilesOptions opt_;
  std::unique_ptr<NetworkFiles> network_;  // a network's files
  std::unique_ptr<AtomicFile> trajectory_, envelope_, events_;
  // the rows' text is made on writer threads (after the files, so they stop first)
  std::unique_ptr<DeferredRows> trajectory_text_, envelope_text_, events_text_;
  std::vector<double> scratch_;  // one row's numbers on their way to a writer
  long trajectory_rows_ = 0, envelope_rows_ = 0, event_rows_ = 0;
  EventObserver observer_;
  RunSink* tap_ = nullptr;
  std::function<void(double)> progress_;
  bool stop_thrown_ = false;
  RegimeWindow window_;
  EnvelopeDecimator plot_;
};

// What summary.json says of a run's report (a single rig's or a network's): model, engine,
// integrator, accuracy, counts {steps, escapements[], stick_slip, slip_reversals, rhs_evals,
// events}, wall_seconds, engine_seconds, write_seconds, complete, failure (when incomplete),
// energy {...} (when the report has a ledger).
nlohmann::json reportJson(const RunReport& report);
// A single rig's verdict: regime, regime_window {...}, regime_reason (when given), final {tau,
// A[], psi[]} (a network's: NetworkFiles::verdictJson, tools/report/network_files.h).
nlohmann::json verdictJson(const RunReport& report, const RegimeVerdict& verdict);
// The per-model part of compare's summary.json: both of the above.
nlohmann::json reportJson(const RunReport& report, const RegimeVerdict& verdict);

// summary.json's `energy` (the ledger, in J) and the timings `wall_seconds`, `engine_seconds`:
// the same keys for a single run and a network's (tools/report/network_files.h).
nlohmann::json energyJson(const EnergyLedger& ledger);
void addTimings(nlohmann::json& summary, double wall_seconds, double engine_seconds);

// summary.json of `run`, the one builder for a single rig and a network: reportJson, the run's
// `verdict` keys, and units, rig, version, command.
nlohmann::json runSummaryJson(const std::string& rig_name, Units units, const RunReport& report,
                              const nlohmann::json& verdict);
// ... of a single rig: its verdictJson with the metronomes' names and `scaled` (the object
// `scale --json` prints).
nlohmann::json runSummaryJson(const Rig& rig, const nlohmann::json& scaled, const RunReport& report,
                              const RegimeVerdict& verdict);

// The reproducibility keys of a summary (docs/outputs.md): `resolved_rig` (the rig after --set,
// the JSON text of resolvedRigJson), `command_line` (argv, tools/report/build_info.h) and `build`
// {metrosync, commit, simbody, eigen}.
void addProvenance(nlohmann::json& summary, const std::string& resolved_rig_json);

// Writes `j` (pretty-printed, newline-terminated) to DIR/summary.json atomically.
void writeSummary(const OutputDir& dir, const nlohmann::json& j);

}  // namespace metrosync
