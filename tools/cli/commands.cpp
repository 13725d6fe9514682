#include "tools/cli/commands.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "base/number_text.h"
#include "models/network_text.h"
#include "models/scaling.h"
#include "sim/analysis/compare.h"
#include "sim/analysis/linear_decay.h"
#include "sim/analysis/regime.h"
#include "sim/record/atomic_file.h"
#include "tools/cli/engines.h"
#include "tools/cli/exit_codes.h"
#include "tools/cli/phase_clock.h"
#include "tools/cli/range_warnings.h"
#include "tools/report/comparison_csv.h"
#include "tools/report/json_file.h"
#include "tools/report/network_files.h"
#include "tools/report/network_plot.h"
#include "tools/report/outputs.h"
#include "tools/report/plot.h"
#include "tools/report/progress_log.h"
#include "tools/report/run_columns.h"
#include "tools/report/scale_report.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string rigDisplayName(const Options& opt) {
  return opt.rig_path.empty() ? "<default rig>" : opt.rig_path;
}

std::string joined(const std::vector<std::string>& v, const std::string& sep = ", ") {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

// the numbers separated by spaces, numberText(x, precision, notation) each
std::string fmtList(const std::vector<double>& v, int precision = 4,
                    Notation notation = Notation::General) {
  std::string s;
  for (double x : v) s += (s.empty() ? "" : " ") + numberText(x, precision, notation);
  return s;
}

// A rig with everything a command needs, checked before anything is written (SPEC 5).
struct LoadedRig {
  std::string text;  // the rig file's text (the default rig's), before the overrides
  Rig rig;
  ScaledParams scaled;
  nlohmann::json scaled_json;
  const Engine* engine = nullptr;  // run: the one that runs; compare: the full model's
};

// `model`: run's --model ("" = the engine's own), "full" for compare, "" for scale.
// The rig's text: the Python module's, else the file's, else the built-in rig's.
std::string rigText(const Options& opt) {
  return opt.rig_text           ? *opt.rig_text
         : opt.rig_path.empty() ? defaultRigYaml()
                                : readRigFile(opt.rig_path);
}

// `loaded`: the rig as the caller loaded it from `text` (else rigText(opt)) with opt.sets (run: its
// network's loader), else loaded here.
LoadedRig loadAndCheck(const Options& opt, const std::string& model,
                       std::optional<Rig> loaded = std::nullopt,
                       std::optional<std::string> text = std::nullopt) {
  LoadedRig r;
  // issue 17: the output limit and the integrator's name, located in the rig
  const LoadOptions lo = engineLoadOptions(opt.max_output);
  r.text = text ? std::move(*text) : rigText(opt);
  r.rig = loaded ? std::move(*loaded) : loadRigText(r.text, rigDisplayName(opt), opt.sets, lo);
  checkSensibleRanges(r.text, rigDisplayName(opt), opt.sets, opt.strict);

  // the integrator is the engine's business, so the loader leaves its name to us
  r.engine = &chooseEngine(opt.engine, model, r.rig, rigDisplayName(opt));

  try {
    r.scaled = computeScaled(r.rig);
  } catch (const std::invalid_argument& e) {
    throw RigError(rigDisplayName(opt) + ": " + e.what());
  }
  r.scaled_json = scaleJson(r.rig, r.scaled);
  return r;
}

// The output directory, created only now that the rig is valid; stale outputs of an earlier
// command there are removed so that every file in it belongs to this run. None with no_files.
std::optional<OutputDir> openOutputDir(const Options& opt, const std::string& rig_name,
                                       const std::string& command) {
  if (opt.no_files) return std::nullopt;
  const std::string path =
      opt.out.empty() ? defaultOutputDir(rig_name, command, opt.sets) : opt.out;
  try {
    OutputDir dir(path);
    dir.removeStaleOutputs();
    return dir;
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("--out: ") + e.what());
  }
}

// Seconds per unit of slow time for a physical rig (t_s columns, plot axes); 0 for a scaled rig.
double secondsPerTau(const LoadedRig& r) {
  return r.rig.units == Units::Physical ? r.scaled.time_scale_s / r.scaled.epsilon : 0.0;
}

PlotStyle plotStyle(const Options& opt, const LoadedRig& r) {
  PlotStyle s;
  s.format = opt.plot_format;
  s.seconds_per_tau = secondsPerTau(r);
  return s;
}

// Where a run makes its rows and their text (RunSink::RecordingThread): as the engine judges, or,
// for benches, METROSYNC_RECORDING_THREAD=never (no recording thread; the text on writer threads),
// always (a recording thread, which writes the text) or inline (everything on the run's thread)
// (docs/bench/speed/run.md, the runcost variants).
void chooseRecordingThread(RunFilesOptions& o) {
  const char* v = std::getenv("METROSYNC_RECORDING_THREAD");
  const std::string s = v ? v : "";
  if (s.empty()) {
    o.recording_thread = RunSink::RecordingThread::WhenLong;
  } else if (s == "never" || s == "inline") {
    o.recording_thread = RunSink::RecordingThread::Never;
    o.text_on_rows_thread = s == "inline";
  } else if (s == "always") {
    o.recording_thread = RunSink::RecordingThread::Always;
  } else {
    throw UsageError("METROSYNC_RECORDING_THREAD=" + s +
                     ": expected never, always or inline (unset: the engine chooses)");
  }
}

RunFilesOptions sinkOptions(const LoadedRig& r, bool trajectory, const std::string& envelope) {
  RunFilesOptions o;
  o.n_metronomes = static_cast<int>(r.rig.metronomes.size());
  o.tau_end = r.scaled.tau_end;
  o.trajectory = trajectory;
  o.events = trajectory;  // events.csv beside the full model's trajectory
  o.envelope_name = envelope;
  o.seconds = r.rig.units == Units::Physical;
  o.epsilon = r.scaled.epsilon;
  o.time_unit = r.rig.units == Units::Physical ? r.scaled.time_scale_s : 1.0;
  o.envelope_platform = !trajectory;  // the slow flow's `uncoupled` rule (sim/analysis/regime.h)
  o.x_unit = r.rig.units == Units::Physical ? r.scaled.x_scale_m : 1.0;
  o.law = r.scaled.friction;
  chooseRecordingThread(o);  // one run at a time: rows beside the integration
  return o;
}

// A model's sink: writing into `dir`, or without one only judging the rows; every row also to
// `keep` when given (the Python module's rows in memory).
std::unique_ptr<FileSink> makeSink(const std::optional<OutputDir>& dir, const RunFilesOptions& o,
                                   std::optional<RunColumns>* keep) {
  auto sink = dir ? std::make_unique<FileSink>(*dir, o) : std::make_unique<FileSink>(o);
  if (keep) sink->setTap(&keep->emplace(o));
  return sink;
}

// summary.json's resolved_rig, command_line and build (docs/outputs.md)
// (`text` loaded with opt.sets before: a single rig by loadAndCheck, a network by its loader)
void addRunProvenance(nlohmann::json& summary, const Options& opt, const std::string& text) {
  addProvenance(summary, resolvedRigJson(text, rigDisplayName(opt), opt.sets, true));
}

// A line every 10% of a long run on stderr when it is not a terminal (logs, CI).
std::unique_ptr<ProgressLog> attachProgress(const Options& opt, const LoadedRig& r, FileSink& sink,
                                            const std::string& what) {
  if (!ProgressLog::wanted(opt.quiet)) return nullptr;
  auto log = std::make_unique<ProgressLog>(what, "tau", r.scaled.tau_end, [](const std::string& l) {
    std::cerr << l << "\n" << std::flush;
  });
  ProgressLog* p = log.get();
  sink.setProgress([p](double tau) { p->update(tau); });
  return log;
}

// Runs `run` (an engine's run into a FileSink). An engine that lets an interruption (or a
// SimulationFailure) through still gives a report: incomplete, with what the sink saw; `physical`:
// its times are seconds.
template <class Run>
RunReport guardedRun(const Engine& engine, bool physical, Run run) {
  const Clock::time_point t0 = Clock::now();
  auto incomplete = [&](double t, const std::string& why) {
    RunReport rep;
    rep.model = engine.model();
    rep.engine = engine.name();
    rep.complete = false;
    rep.failure = "stopped at t = " + numberText(t) + (physical ? " s" : "") + ": " + why;
    rep.wall_seconds = secondsSince(t0);
    return rep;
  };
  try {
    return run();
  } catch (const RunInterrupted& e) {
    return incomplete(e.t, e.what());
  } catch (const SimulationFailure& f) {
    return incomplete(f.t, f.why);
  }
}

RunReport runModel(const Engine& engine, const LoadedRig& r, FileSink& sink) {
  return guardedRun(engine, r.rig.units == Units::Physical,
                    [&] { return engine.run(r.rig, sink); });
}

// The regime of a finished run ("unknown" when it stopped early), and a final row for the
// summary if the engine left it empty.
RegimeVerdict judge(RunReport& report, const FileSink& sink, const LoadedRig& r) {
  const RegimeWindow& w = sink.regimeWindow();
  if (report.final_row.A.empty() && !w.empty()) report.final_row = w.last();
  if (!report.complete) {
    RegimeVerdict v;
    v.window_tau_start = w.tauStart();
    return v;
  }
  return classifyRegime(w, r.scaled.theta_c, r.scaled.locked);
}

std::string modelTitle(const std::string& model) {
  return model == "full" ? "full model" : "slow flow";
}

// The final state: each swinging metronome's amplitude against its threshold; a rig whose
// metronomes are all locked (section 3A) has neither, and its board's linear decay is the result.
void printFinalState(const LoadedRig& r, const RunReport& rep, const LinearDecay* decay) {
  std::cout << "  final tau = " << numberText(rep.final_row.tau, 4);
  if (r.rig.numSwinging() == 0) {
    std::cout << ": every metronome locked";
    const auto s3a = decay ? decay->result(r.rig) : std::nullopt;
    if (s3a)
      std::cout << "; the board's extremes decay linearly (section 3A): slope "
                << numberText(s3a->slope_m_s, 4) << " m/s, mu-bar " << numberText(s3a->mu_bar, 4)
                << ", period " << numberText(s3a->period_s, 4) << " s, " << s3a->extremes
                << " extremes";
    return;
  }
  std::cout << ": A = " << fmtList(rep.final_row.A) << " (theta_c = " << fmtList(r.scaled.theta_c)
            << ")";
  if (!rep.final_row.psi.empty()) std::cout << ", psi = " << fmtList(rep.final_row.psi);
}

void printRunSummary(const std::string& model, const LoadedRig& r, const RunReport& rep,
                     const RegimeVerdict& v, const LinearDecay* decay = nullptr) {
  std::cout << modelTitle(model) << " (" << rep.engine
            << (rep.integrator.empty() ? "" : ", " + rep.integrator) << "): regime "
            << regimeName(v) << "\n";
  printFinalState(r, rep, decay);
  std::cout << "\n  " << rep.counts.steps << " steps";
  if (!rep.counts.escapements.empty()) {
    std::vector<double> e(rep.counts.escapements.begin(), rep.counts.escapements.end());
    std::cout << ", escapements " << fmtList(e, 0, Notation::Fixed);
  }
  if (model == "full")
    std::cout << ", " << rep.counts.stick_slip << " stick-slip switches, "
              << rep.counts.slip_reversals << " slip reversals";
  std::cout << ", wall time " << numberText(rep.wall_seconds, 3) << " s\n";
}

void printFiles(const std::optional<OutputDir>& dir, const std::vector<std::string>& files) {
  if (dir) std::cout << "files: " << dir->path() << "/ (" << joined(files) << ")\n";
}

// Said on stderr with a folder (the CLI's); without one the caller raises it (Python).
void reportFailure(const std::string& model, const std::string& failure,
                   const std::optional<OutputDir>& dir) {
  if (!dir) return;
  std::cerr << "metrosync: error: " << modelTitle(model) << ": " << failure
            << "\nmetrosync: the files written so far are in " << dir->path()
            << "/ (summary.json says complete: false)\n";
}

// summary.json's "files" (and the file itself, last: a summary.json means the run's files are
// all there), with a folder, summary.json added to `files`; without one an empty list.
void finishSummary(nlohmann::json& summary, const std::optional<OutputDir>& dir,
                   std::vector<std::string>& files) {
  if (!dir) {
    summary["files"] = nlohmann::json::array();
    return;
  }
  files.push_back("summary.json");
  summary["files"] = files;
  writeSummary(*dir, summary);
}

// section 3A (locked metronomes, board on springs): the extremes are the platform's stops
void observeSection3A(const LoadedRig& r, bool full, FileSink& sink, LinearDecay& decay) {
  if (full && isSection3ARig(r.rig))
    sink.setEventObserver([&decay](const char*, int who, const std::vector<double>&,
                                   const std::vector<double>& after) {
      if (who < 0) decay.addExtreme(after[0], after[1]);
    });
}

void addSection3A(nlohmann::json& summary, const LinearDecay& decay, const Rig& rig) {
  if (const auto s3a = decay.result(rig))
    summary["section3a"] = {{"slope", s3a->slope_m_s},
                            {"mu_bar", s3a->mu_bar},
                            {"period", s3a->period_s},
                            {"extremes", s3a->extremes}};
}

// What `run` runs (docs/architecture.md, "One run"): the network its file holds (a single rig is
// the network of one), parsed once, and the engine chosen for it by the one chooser; a single
// rig's scales besides (its summary, plot and printed state).
struct RunSubject {
  std::string text;  // the rig file's text, before the overrides
  Network net;
  std::optional<LoadedRig> rig;  // a single rig's; empty for a network of several platforms
  const Engine* engine = nullptr;
  bool physical() const { return !rig || rig->rig.units == Units::Physical; }
};

RunSubject loadRunSubject(const Options& opt) {
  RunSubject s;
  s.text = rigText(opt);
  s.net = loadNetworkText(s.text, rigDisplayName(opt), opt.sets, engineLoadOptions(opt.max_output));
  if (s.net.isSingleRig()) {
    s.rig = loadAndCheck(opt, opt.model, s.net.toSingleRig(), s.text);
    s.engine = s.rig->engine;
    return s;
  }
  checkSensibleRanges(s.text, rigDisplayName(opt), opt.sets, opt.strict);
  s.engine = &chooseEngine(opt.engine, opt.model, s.net, rigDisplayName(opt), "runs");
  if (opt.no_files)  // docs/networks.md: its rows are in files only
    throw UsageError(rigDisplayName(opt) + ": a " + networkOfPlatforms(s.net.platforms.size()) +
                     " keeps its rows in files only: give it a folder");
  return s;
}

// The run's sink: a single rig's files (its rows also to `keep`: the Python module's), or a
// network's (tools/report/network_files.h).
std::unique_ptr<FileSink> makeRunSink(const RunSubject& s, const std::optional<OutputDir>& dir,
                                      bool full, std::optional<RunColumns>* keep) {
  if (!s.rig) return std::make_unique<FileSink>(*dir, s.net);
  return makeSink(dir, sinkOptions(*s.rig, full, "envelope.csv"), keep);
}

// A finished run's verdict: its label, and a single rig's regime (SPEC 4) or a network's keys.
struct RunVerdict {
  std::string label;
  RegimeVerdict rig;
  nlohmann::json network;
};

RunVerdict verdictOf(const RunSubject& s, RunReport& report, const FileSink& sink) {
  RunVerdict v;
  if (s.rig) {
    v.rig = judge(report, sink, *s.rig);
    v.label = regimeName(v.rig);
  } else {
    v.network = sink.network()->verdictJson(report);
    v.label = v.network["network"]["regime"].get<std::string>();
  }
  return v;
}

// The run's plots in `dir`, their file names: a single rig's envelope, a network's boards.
std::vector<std::string> plotRun(const Options& opt, const RunSubject& s, const std::string& model,
                                 const FileSink& sink, const RunVerdict& v, const OutputDir& dir) {
  if (!s.rig)
    return plotNetwork(dir, *sink.network(), s.net, s.net.name + " - " + v.label, opt.plot_format);
  const LoadedRig& r = *s.rig;
  const std::string plot = "envelope." + opt.plot_format;
  if (plotEnvelope(dir, plot, sink.plotRows(), r.scaled.theta_c,
                   r.rig.name + " - " + modelTitle(model) + " - " + v.label, plotStyle(opt, r)))
    return {plot};
  return {};
}

nlohmann::json summaryOf(const RunSubject& s, const RunReport& report, const RunVerdict& v,
                         const LinearDecay& decay) {
  if (!s.rig) return runSummaryJson(s.net.name, Units::Physical, report, v.network);
  nlohmann::json summary = runSummaryJson(s.rig->rig, s.rig->scaled_json, report, v.rig);
  addSection3A(summary, decay, s.rig->rig);
  return summary;
}

void printRun(const RunSubject& s, const std::string& model, const RunReport& report,
              const RunVerdict& v, const LinearDecay& decay, const nlohmann::json& summary) {
  if (s.rig) return printRunSummary(model, *s.rig, report, v.rig, &decay);
  std::cout << networkOfPlatforms(s.net.platforms.size()) << " (" << s.engine->name() << ", "
            << report.integrator << "): " << v.label
            << ", r = " << summary["network"]["r"].get<double>() << "\n";
}

// `run`, one path for a single rig and a network of platforms; a single rig's rows also kept
// when `keep`. METROSYNC_PHASES=1: each phase's end on stderr (tools/cli/phase_clock.h)
RunOutcome runImpl(const Options& opt, bool keep) {
  markPhase("args");
  const RunSubject s = loadRunSubject(opt);
  markPhase("rig");
  const Engine& engine = *s.engine;
  const std::string model = engine.model();
  installStopHandlers();  // before any file exists, so that no signal can leave a bare .part
  const bool full = model == "full";
  // each model its own default folder: `run` then `run --model slow` keep both runs' files
  const std::optional<OutputDir> dir = openOutputDir(opt, s.net.name, full ? "run" : "run-slow");

  // the run's files made durable with one sync (sim/record/atomic_file.h): all of them and
  // summary.json with --no-plot; else the result files, then the plot and summary.json
  CommitBatch durable;
  RunOutcome out;
  const auto sink = makeRunSink(s, dir, full, keep ? &out.rows : nullptr);
  LinearDecay decay;
  if (s.rig) observeSection3A(*s.rig, full, *sink, decay);
  const auto progress = s.rig ? attachProgress(opt, *s.rig, *sink, "run") : nullptr;
  markPhase("folder");
  RunReport report = guardedRun(engine, s.physical(), [&] { return engine.run(s.net, *sink); });
  markPhase("run");
  report.write_seconds = sink->commit();
  markPhase("files");
  const RunVerdict verdict = verdictOf(s, report, *sink);

  std::vector<std::string> files = sink->fileNames();
  // the result files on disk before the plot (a gnuplot child, ~0.1 s); summary.json then
  // follows on its own
  if (dir && !opt.no_plot) {
    durable.finish();
    markPhase("sync");
    for (const std::string& png : plotRun(opt, s, model, *sink, verdict, *dir))
      files.push_back(png);
    markPhase("plot");
  }

  out.summary = summaryOf(s, report, verdict, decay);
  addRunProvenance(out.summary, opt, s.text);
  finishSummary(out.summary, dir, files);
  markPhase("summary");
  if (durable.active()) {
    durable.finish();  // --no-plot: renamed in order, summary.json last
    markPhase("sync");
  }

  if (!opt.quiet) {
    printRun(s, model, report, verdict, decay, out.summary);
    printFiles(dir, files);
  }
  markPhase("print");
  out.code = report.complete ? kSuccess : kSimulationFailed;
  if (!report.complete) reportFailure(model, report.failure, dir);
  return out;
}

}  // namespace

int runCommand(const Options& opt) {
  return runImpl(opt, false).code;
}

RunOutcome runKeepingRows(const Options& opt) {
  return runImpl(opt, true);
}

namespace {

// The slow flow of compare, unless a signal stopped the full model.
RunReport runSlowOfCompare(const LoadedRig& r, FileSink& sink) {
  if (!FileSink::stopRequested()) return runModel(*findEngine("slowflow"), r, sink);
  RunReport slow;
  slow.model = "slow";
  slow.engine = "slowflow";
  slow.complete = false;
  slow.failure = "not run: interrupted by a signal";
  return slow;
}

// The comparison of the two envelopes: from the files with a folder (streaming, as the CLI's),
// and from the rows kept in memory (comparison.csv's columns; the summary's too without files).
ComparisonResult compareModels(const LoadedRig& r, const std::optional<OutputDir>& dir,
                               RunOutcome& out, bool keep) {
  ComparisonResult cmp;
  if (keep)
    cmp = comparisonColumns(static_cast<int>(r.rig.metronomes.size()), out.rows->envelopeRows(),
                            out.slow_rows->envelopeRows(), r.scaled.epsilon, secondsPerTau(r),
                            out.comparison);
  if (dir)
    cmp = compareEnvelopeFiles(dir->file("envelope_full.csv"), dir->file("envelope_slow.csv"),
                               r.scaled.epsilon, dir->file("comparison.csv"), secondsPerTau(r));
  return cmp;
}

// compare's summary: SPEC keys at the top level are the full model's (the reference); each
// model's own report is under models.full / models.slow
nlohmann::json compareSummary(const LoadedRig& r, const RunReport& full, const RunReport& slow,
                              const RegimeVerdict& v_full, const RegimeVerdict& v_slow,
                              const ComparisonResult& cmp) {
  const nlohmann::json jf = reportJson(full, v_full), js = reportJson(slow, v_slow);
  nlohmann::json summary = runSummaryJson(r.rig, r.scaled_json, full, v_full);
  summary["command"] = "compare";
  summary["model"] = "compare";
  summary["models"] = {{"full", jf}, {"slow", js}};
  summary["comparison"] = comparisonJson(cmp);
  summary["complete"] = full.complete && slow.complete;
  summary.erase("failure");
  if (!full.complete || !slow.complete) {
    std::string why;
    if (!full.complete) why += "full: " + full.failure;
    if (!slow.complete) why += std::string(why.empty() ? "" : "; ") + "slow: " + slow.failure;
    summary["failure"] = why;
  }
  return summary;
}

void printCompare(const LoadedRig& r, const RunReport& full, const RunReport& slow,
                  const RegimeVerdict& v_full, const RegimeVerdict& v_slow,
                  const ComparisonResult& cmp) {
  printRunSummary("full", r, full, v_full);
  printRunSummary("slow", r, slow, v_slow);
  std::cout << "full - slow over " << cmp.rows << " rows: max |dA| = " << fmtList(cmp.max_abs_dA);
  if (!cmp.max_abs_dpsi.empty())
    std::cout << ", max |dpsi| (mod 2 pi) = " << fmtList(cmp.max_abs_dpsi);
  std::cout << "\n";
}

// `compare`, each model's rows also kept when `keep`.
RunOutcome compareImpl(const Options& opt, bool keep) {
  RunOutcome out;
  const Engine* requested = findEngine(opt.engine);
  if (requested && requested->model() != "full")
    throw UsageError("--engine " + opt.engine + ": compare runs the full model (--engine " +
                     engineNames("full") + ") against the slow flow");
  LoadedRig r = loadAndCheck(opt, "full");
  requireSlowFlow(r.rig, rigDisplayName(opt));  // before anything is written
  installStopHandlers();
  const std::optional<OutputDir> dir = openOutputDir(opt, r.rig.name, "compare");
  const Clock::time_point t0 = Clock::now();

  const auto full_sink =
      makeSink(dir, sinkOptions(r, true, "envelope_full.csv"), keep ? &out.rows : nullptr);
  const auto full_progress = attachProgress(opt, r, *full_sink, "compare (full model)");
  RunReport full = runModel(*r.engine, r, *full_sink);
  full.write_seconds = full_sink->commit();

  const auto slow_sink =
      makeSink(dir, sinkOptions(r, false, "envelope_slow.csv"), keep ? &out.slow_rows : nullptr);
  const auto slow_progress = attachProgress(opt, r, *slow_sink, "compare (slow flow)");
  RunReport slow = runSlowOfCompare(r, *slow_sink);
  slow.write_seconds = slow_sink->commit();

  const RegimeVerdict v_full = judge(full, *full_sink, r);
  const RegimeVerdict v_slow = judge(slow, *slow_sink, r);
  const ComparisonResult cmp = compareModels(r, dir, out, keep);

  std::vector<std::string> files = full_sink->fileNames();
  for (const auto& f : slow_sink->fileNames()) files.push_back(f);
  if (dir) files.push_back("comparison.csv");
  const std::string plot = "comparison." + opt.plot_format;
  if (dir && !opt.no_plot &&
      plotComparison(*dir, plot, full_sink->plotRows(), slow_sink->plotRows(), r.scaled.theta_c,
                     r.rig.name + " - full model (solid) " + regimeName(v_full) +
                         ", slow flow (dashed) " + regimeName(v_slow),
                     plotStyle(opt, r)))
    files.push_back(plot);

  out.summary = compareSummary(r, full, slow, v_full, v_slow, cmp);
  out.summary["wall_seconds"] = secondsSince(t0);
  addRunProvenance(out.summary, opt, r.text);
  finishSummary(out.summary, dir, files);

  if (!opt.quiet) {
    printCompare(r, full, slow, v_full, v_slow, cmp);
    printFiles(dir, files);
  }
  out.code = kSuccess;
  if (!full.complete) reportFailure("full", full.failure, dir), out.code = kSimulationFailed;
  if (!slow.complete) reportFailure("slow", slow.failure, dir), out.code = kSimulationFailed;
  return out;
}

}  // namespace

int compareCommand(const Options& opt) {
  return compareImpl(opt, false).code;
}

RunOutcome compareKeepingRows(const Options& opt) {
  return compareImpl(opt, true);
}

namespace {
LoadedRig loadForScale(const Options& opt) {
  Options no_output = opt;  // scale writes no file: no output limit
  no_output.max_output = HUGE_VAL;
  return loadAndCheck(no_output, "");
}
}  // namespace

int scaleCommand(const Options& opt) {
  const LoadedRig r = loadForScale(opt);
  checkFiniteJson("scale --json", r.scaled_json);
  if (opt.json)
    std::cout << r.scaled_json.dump(2) << "\n";
  else
    std::cout << scaleText(r.rig, r.scaled);
  return kSuccess;
}

std::string scaledJsonText(const Options& opt) {
  return loadForScale(opt).scaled_json.dump(2);
}

}  // namespace metrosync::cli
