#include "tools/report/outputs.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "base/number_text.h"
#include "sim/record/private_dir.h"
#include "tools/report/build_info.h"
#include "tools/report/json_file.h"
#include "tools/report/network_files.h"

namespace metrosync {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// EnvelopeDecimator

void EnvelopeDecimator::add(const EnvelopeRow& row) {
  if (seen_++ % static_cast<long>(stride_) == 0) {
    kept_.push_back(row);
    if (kept_.size() >= 2 * max_rows_) {
      // keep rows 0, 2, 4, ...: they are exactly the multiples of the doubled stride
      size_t w = 0;
      for (size_t r = 0; r < kept_.size(); r += 2) kept_[w++] = std::move(kept_[r]);
      kept_.resize(w);
      stride_ *= 2;
    }
  }
  last_ = row;
  have_last_ = true;
}

std::vector<EnvelopeRow> EnvelopeDecimator::rows() const {
  std::vector<EnvelopeRow> out = kept_;
  if (have_last_ && (out.empty() || out.back().tau != last_.tau)) out.push_back(last_);
  return out;
}

// ---------------------------------------------------------------------------------------------
// FileSink

namespace {
volatile std::sig_atomic_t g_stop_requested = 0;
}

void FileSink::requestStop() {
  g_stop_requested = 1;
}
bool FileSink::stopRequested() {
  return g_stop_requested != 0;
}
void FileSink::clearStopRequest() {
  g_stop_requested = 0;
}

namespace {

// the kinds of events.csv (docs/outputs.md), numbered so that a row's kind travels as a number
constexpr const char* kEventKinds[] = {"tick", "stick", "slip"};

double eventKindIndex(const char* kind) {
  for (size_t k = 0; k < std::size(kEventKinds); ++k)
    if (std::strcmp(kind, kEventKinds[k]) == 0) return static_cast<double>(k);
  throw std::logic_error(std::string("unknown event kind ") + kind);
}

// the n numbers, comma-separated, written in place at the line's end (room made once); false when
// one of them is not finite (written as printf would, for the text check to name it)
bool appendNumbers(const double* v, size_t n, std::string& line) {
  if (n == 0) return true;
  const size_t at = line.size();
  line.resize(at + n * (kMaxGeneralChars + 1));
  char* const begin = line.data();
  char* out = begin + at;
  bool finite = true;
  for (size_t k = 0; k < n; ++k) {
    if (k) *out++ = ',';
    if (v[k] != v[k]) {
      std::memcpy(out, "nan", 3);
      out += 3;
      finite = false;
    } else {
      finite = std::isfinite(v[k]) && finite;
      out = writeGeneral(v[k], 12, out);
    }
  }
  line.resize(static_cast<size_t>(out - begin));
  return finite;
}

// %.12g of v at the line's end; false when v is not finite
bool appendNumber(double v, std::string& line) {
  return appendNumbers(&v, 1, line);
}

}  // namespace

FileSink::FileSink(const RunFilesOptions& opt)
    : opt_(opt), window_(opt.tau_end, opt.epsilon), plot_(opt.max_plot_rows) {
  if (opt_.n_metronomes < 1) throw std::invalid_argument("FileSink: no metronome");
  if (opt_.envelope_platform) window_.setEnvelopePlatform(opt_.law);
}

FileSink::FileSink(const OutputDir& dir, const RunFilesOptions& opt) : FileSink(opt) {
  const size_t n = static_cast<size_t>(opt_.n_metronomes);
  if (opt_.trajectory) {
    trajectory_ = std::make_unique<AtomicFile>(dir.file(opt_.trajectory_name));
    // t is in seconds already for a physical rig (SPEC 3)
    trajectory_->writeLine(trajectoryHeader(opt_.n_metronomes));
    trajectory_text_ = std::make_unique<DeferredRows>(
        *trajectory_, 2 * n + 4, [w = 2 * n + 4](const double* row, std::string& line) {
          return appendNumbers(row, w, line);
        });
    if (opt_.events) {
      events_ = std::make_unique<AtomicFile>(dir.file(opt_.events_name));
      events_->writeLine(eventsHeader(opt_.n_metronomes, opt_.seconds));
      events_text_ = std::make_unique<DeferredRows>(*events_, 3 + 2 * (2 * n + 3), eventFormat());
    }
  }
  envelope_ = std::make_unique<AtomicFile>(dir.file(opt_.envelope_name));
  envelope_->writeLine(envelopeHeader(opt_.n_metronomes) + (opt_.seconds ? ",t_s" : ""));
  envelope_text_ = std::make_unique<DeferredRows>(*envelope_, 2 * n + 1, envelopeFormat());
  if (opt_.text_on_rows_thread) textOnRowsThread();
}

void FileSink::textOnRowsThread() {
  for (DeferredRows* w : {trajectory_text_.get(), envelope_text_.get(), events_text_.get()})
    if (w) w->writeOnCallersThread();
}

// an event's numbers: kind (its index in kEventKinds), who (-1: the platform), t, then the rows
// before and after without their t. Its words (a kind, "platform", a metronome's number) are this
// file's own and none spells a non-finite number: the row is checked by its numbers alone.
DeferredRows::Format FileSink::eventFormat() const {
  const size_t width = 2 * static_cast<size_t>(opt_.n_metronomes) + 3;
  return [width, eps = opt_.epsilon, unit = opt_.time_unit, seconds = opt_.seconds](
             const double* v, std::string& line) {
    const double t = v[2];
    const int who = static_cast<int>(v[1]);
    bool finite = appendNumber(t, line);
    line += ',';
    finite = appendNumber(eps * t / unit, line) && finite;
    line += ',';
    line += kEventKinds[static_cast<size_t>(v[0])];
    line += ',';
    line += who < 0 ? std::string("platform") : std::to_string(who + 1);
    line += ',';
    finite = appendNumbers(v + 3, 2 * width, line) && finite;
    if (seconds) {
      line += ',';
      finite = appendNumber(t, line) && finite;
    }
    return finite;
  };
}

// an envelope row's numbers: tau, A_1..A_N, psi_1..psi_N-1, r (NaN: computed from A and psi)
DeferredRows::Format FileSink::envelopeFormat() const {
  const size_t n = static_cast<size_t>(opt_.n_metronomes);
  return [n, eps = opt_.epsilon, unit = opt_.time_unit, seconds = opt_.seconds](const double* v,
                                                                                std::string& line) {
    EnvelopeRow row;
    row.tau = v[0];
    row.A.assign(v + 1, v + 1 + n);
    row.psi.assign(v + 1 + n, v + 2 * n);
    row.r = v[2 * n];
    line += formatEnvelopeRow(row);
    if (seconds) line += "," + numberText(row.tau / eps * unit, 12);
    return false;  // a row a period: read by the text check
  };
}

std::string trajectoryHeader(int n) {
  std::string h = "t,x,xdot";
  for (int i = 1; i <= n; ++i)
    h += ",theta_" + std::to_string(i) + ",thetadot_" + std::to_string(i);
  return h + ",platform";
}

std::string eventsHeader(int n, bool seconds) {
  std::string h = "t,tau,kind,who";
  for (const char* when : {"_before", "_after"}) {
    h += std::string(",x") + when + ",xdot" + when;
    for (int i = 1; i <= n; ++i)
      h += ",theta_" + std::to_string(i) + when + ",thetadot_" + std::to_string(i) + when;
    h += std::string(",platform") + when;
  }
  return h + (seconds ? ",t_s" : "");
}

void FileSink::eventRecord(const char* kind, int metronome, const std::vector<double>& before,
                           const std::vector<double>& after) {
  if (!wantsEventRecords()) return;
  const size_t want = 2 * static_cast<size_t>(opt_.n_metronomes) + 4;
  if (before.size() != want || after.size() != want)
    throw std::logic_error("event record of the wrong width");
  if (events_text_) {
    scratch_.assign({eventKindIndex(kind), static_cast<double>(metronome), after[0]});
    scratch_.insert(scratch_.end(), before.begin() + 1, before.end());
    scratch_.insert(scratch_.end(), after.begin() + 1, after.end());
    events_text_->add(scratch_.data());
  }
  ++event_rows_;
  if (tap_) tap_->eventRecord(kind, metronome, before, after);
  if (observer_) observer_(kind, metronome, before, after);
}

void FileSink::checkStop(double t) {
  if (!stopRequested() || stop_thrown_) return;
  stop_thrown_ = true;  // once: the engine may still hand over its final state
  throw RunInterrupted(t, "interrupted by a signal");
}

void FileSink::eventRow(const char*, const std::vector<double>& row) {
  if (row.size() > 2) window_.platformMode(static_cast<int>(row.back()), row[1] / opt_.x_unit);
}

void FileSink::trajectoryRow(const std::vector<double>& row) {
  if (row.size() > 2) window_.platformMode(static_cast<int>(row.back()), row[1] / opt_.x_unit);
  if (!opt_.trajectory) return;
  const size_t want = 2 * static_cast<size_t>(opt_.n_metronomes) + 4;
  if (row.size() != want)
    throw std::logic_error("trajectory row with " + std::to_string(row.size()) +
                           " values, expected " + std::to_string(want));
  if (trajectory_text_) trajectory_text_->add(row.data());
  ++trajectory_rows_;
  if (tap_) tap_->trajectoryRow(row);
  checkStop(row[0]);
}

void FileSink::envelopeRow(const EnvelopeRow& row) {
  if (static_cast<int>(row.A.size()) != opt_.n_metronomes ||
      static_cast<int>(row.psi.size()) != opt_.n_metronomes - 1)
    throw std::logic_error("envelope row of the wrong width");
  if (envelope_text_) {
    scratch_.assign(1, row.tau);
    scratch_.insert(scratch_.end(), row.A.begin(), row.A.end());
    scratch_.insert(scratch_.end(), row.psi.begin(), row.psi.end());
    scratch_.push_back(row.r);
    envelope_text_->add(scratch_.data());
  }
  ++envelope_rows_;
  window_.add(row);
  plot_.add(row);
  if (tap_) tap_->envelopeRow(row);
  if (progress_) progress_(row.tau);
  checkStop(row.tau / opt_.epsilon * opt_.time_unit);
}

FileSink::FileSink(const OutputDir& dir, const Network& net)
    : network_(std::make_unique<NetworkFiles>(dir, net)),
      window_(opt_.tau_end, opt_.epsilon) {}  // unused: a network's verdict is NetworkFiles'

FileSink::~FileSink() = default;

void FileSink::stateSample(double t, const std::vector<double>& y,
                           const std::vector<PlatformMode>& modes) {
  if (!network_) return;
  network_->add(t, y, modes);
  checkStop(t);  // a network's samples are its rows: where a signal stops it
}

double FileSink::commit() {
  const auto t0 = std::chrono::steady_clock::now();
  if (network_) {  // written as they came: what is left is the commit itself
    network_->commit();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  for (DeferredRows* w : {trajectory_text_.get(), envelope_text_.get(), events_text_.get()})
    if (w) w->finish();
  const double waited =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (trajectory_ && trajectory_->open()) trajectory_->commit();
  if (envelope_ && envelope_->open()) envelope_->commit();
  if (events_ && events_->open()) events_->commit();
  return waited;
}

std::vector<std::string> FileSink::fileNames() const {
  if (network_) return network_->fileNames();
  std::vector<std::string> names;
  if (!envelope_) return names;  // no folder
  if (opt_.trajectory) names.push_back(opt_.trajectory_name);
  names.push_back(opt_.envelope_name);
  if (events_) names.push_back(opt_.events_name);
  return names;
}

// ---------------------------------------------------------------------------------------------
// summary.json

nlohmann::json reportJson(const RunReport& report) {
  nlohmann::json j;
  j["model"] = report.model;
  j["engine"] = report.engine;
  j["integrator"] = report.integrator;
  j["accuracy"] = report.accuracy;
  j["counts"] = {
      {"steps", report.counts.steps},           {"escapements", report.counts.escapements},
      {"stick_slip", report.counts.stick_slip}, {"slip_reversals", report.counts.slip_reversals},
      {"rhs_evals", report.counts.rhs_evals},   {"events", report.counts.events}};
  addTimings(j, report.wall_seconds, report.engine_seconds);
  j["write_seconds"] = report.write_seconds;
  j["complete"] = report.complete;
  if (!report.complete) j["failure"] = report.failure;
  if (report.has_ledger) j["energy"] = energyJson(report.ledger);
  return j;
}

nlohmann::json verdictJson(const RunReport& report, const RegimeVerdict& verdict) {
  nlohmann::json j;
  j["regime"] =
      regimeName(verdict);  // the SPEC 4 name; for N >= 3 the clusters' (sim/analysis/regime.h)
  j["regime_window"] = {{"tau_start", verdict.window_tau_start},
                        {"rows", verdict.window_rows},
                        {"psi_range", verdict.psi_range},
                        {"settle_tau_start", verdict.settle_tau_start},
                        {"psi_settle_range", verdict.psi_settle_range},
                        {"alive", verdict.alive},
                        {"clusters", clusterText(verdict.cluster_sizes)},
                        {"cluster_members", verdict.cluster_members},
                        {"cluster_phase", verdict.cluster_phase}};
  // the platform over the window (the `uncoupled` rule): null when not known
  if (verdict.platform_slipped >= 0)
    j["regime_window"]["platform_slipped"] = verdict.platform_slipped == 1;
  else
    j["regime_window"]["platform_slipped"] = nullptr;
  if (verdict.platform_slip_rows >= 0)  // the full model's own slips (docs/regimes.md)
    j["regime_window"]["platform_slip_rows"] = verdict.platform_slip_rows;
  if (verdict.platform_travel >= 0) j["regime_window"]["platform_travel"] = verdict.platform_travel;
  // a platform still in the window: did it slip before (stuck after coupling moved it) or never
  // (`uncoupled`)?
  if (verdict.platform_slipped_before >= 0)
    j["regime_window"]["platform_slipped_before"] = verdict.platform_slipped_before == 1;
  if (!verdict.reason.empty()) j["regime_reason"] = verdict.reason;
  j["final"] = {
      {"tau", report.final_row.tau}, {"A", report.final_row.A}, {"psi", report.final_row.psi}};
  return j;
}

nlohmann::json reportJson(const RunReport& report, const RegimeVerdict& verdict) {
  nlohmann::json j = reportJson(report);
  j.update(verdictJson(report, verdict));
  return j;
}

nlohmann::json energyJson(const EnergyLedger& e) {
  return {{"units", "J"},
          {"initial", e.initial_J},
          {"final", e.final_J},
          {"escapement_in", e.escapement_in_J},
          {"damping_out", e.damping_out_J},
          {"friction_out", e.friction_out_J},
          {"residual", e.residual_J()},
          {"relative_residual", e.relativeResidual()}};
}

void addTimings(nlohmann::json& summary, double wall_seconds, double engine_seconds) {
  summary["wall_seconds"] = wall_seconds;
  summary["engine_seconds"] = engine_seconds;
}

nlohmann::json runSummaryJson(const std::string& rig_name, Units units, const RunReport& report,
                              const nlohmann::json& verdict) {
  nlohmann::json j = reportJson(report);
  j.update(verdict);
  j["command"] = "run";
  j["units"] = toString(units);
  j["rig"] = rig_name;
  j["version"] = metrosyncVersion();
  return j;
}

nlohmann::json runSummaryJson(const Rig& rig, const nlohmann::json& scaled, const RunReport& report,
                              const RegimeVerdict& verdict) {
  nlohmann::json keys = verdictJson(report, verdict);
  std::vector<std::string> names;
  for (const auto& m : rig.metronomes) names.push_back(m.name);
  keys["metronomes"] = names;
  keys["scaled"] = scaled;
  return runSummaryJson(rig.name, rig.units, report, keys);
}

void addProvenance(nlohmann::json& summary, const std::string& resolved_rig_json) {
  summary["resolved_rig"] = nlohmann::json::parse(resolved_rig_json);
  summary["command_line"] = commandLine();
  summary["build"] = buildJson();
}

void writeSummary(const OutputDir& dir, const nlohmann::json& j) {
  // a failed run (exit 3) keeps its summary, a number it never reached null (docs/outputs.md)
  const bool failed = j.is_object() && j.value("complete", true) == false;
  writeJsonFile(dir.file("summary.json"), failed ? nullingNonFinite(j) : j);
}

}  // namespace metrosync
