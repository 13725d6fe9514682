#include "sim/analysis/fit/model_samples.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "base/constants.h"
#include "models/scaling.h"

namespace metrosync {

namespace {

// The run goes this many rows past the requested end, so that the end is inside the record.
constexpr double kEndMarginRows = 2.0;
// Model rows per small-angle period of metronome 1: the Hermite interpolant between rows is then
// ~1e-7 rad off at 45 degrees, four orders below a camera's noise.
constexpr double kRowsPerPeriod = 100.0;

double medianSpacing(const std::vector<double>& t) {
  std::vector<double> d;
  for (std::size_t i = 1; i < t.size(); ++i) d.push_back(t[i] - t[i - 1]);
  if (d.empty()) return 1.0;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

int columnOf(int metronome) {
  return metronome < 0 ? 1 : 3 + 2 * metronome;
}

struct EnvelopeRecorder : RunSink {
  std::vector<EnvelopeRow> rows;
  void envelopeRow(const EnvelopeRow& row) override { rows.push_back(row); }
};

double lastTime(const std::vector<SampleRequest>& requests) {
  double t = 0.0;
  for (const SampleRequest& r : requests) t = std::max(t, r.t_s);
  return t;
}

// A_i at tau, linear between the envelope's rows
double envelopeAt(const std::vector<EnvelopeRow>& rows, double tau, std::size_t i) {
  auto it = std::upper_bound(rows.begin(), rows.end(), tau,
                             [](double v, const EnvelopeRow& n) { return v < n.tau; });
  if (it == rows.begin()) return rows.front().A.at(i);
  if (it == rows.end()) return rows.back().A.at(i);
  const EnvelopeRow &a = *(it - 1), &b = *it;
  const double w = b.tau > a.tau ? (tau - a.tau) / (b.tau - a.tau) : 1.0;
  return a.A.at(i) + w * (b.A.at(i) - a.A.at(i));
}

// The rows and event rows as they come (flat, `width` values each; in time order but for the
// final row), and the event records.
struct KnotRecorder : RunSink {
  std::vector<double> rows;
  std::vector<char> after_event;
  std::size_t width = 0;
  std::vector<EventRecord> events;
  void trajectoryRow(const std::vector<double>& row) override { add(row, false); }
  void eventRow(const char*, const std::vector<double>& row) override { add(row, true); }
  bool wantsEnvelope() const override { return false; }
  bool wantsEventRecords() const override { return true; }
  void eventRecord(const char* kind, int metronome, const std::vector<double>& before,
                   const std::vector<double>& after) override {
    events.push_back({kind, metronome, before, after});
  }
  void add(const std::vector<double>& row, bool event) {
    width = row.size();
    rows.insert(rows.end(), row.begin(), row.end());
    after_event.push_back(event);
  }
};

}  // namespace

double modelRowInterval(const std::vector<double>& t_s, const Rig& rig) {
  const double dt = medianSpacing(t_s);
  const double longest = kTwoPi * computeScaled(rig).time_scale_s / kRowsPerPeriod;
  return dt / std::ceil(dt / longest);
}

ModelTrajectory::ModelTrajectory(const Engine& engine, Rig rig, double t_end_s, double row_dt_s)
    : rig_(std::move(rig)) {
  rig_.sim.sample_s = row_dt_s;
  rig_.sim.t_end_s = t_end_s + kEndMarginRows * row_dt_s;
  KnotRecorder rec;
  // the rows' room (the metronomes' columns and t, x, xdot, platform), and as much again for the
  // event rows, so that the rows are not moved as they come
  const std::size_t rows = static_cast<std::size_t>(rig_.sim.t_end_s / row_dt_s) + 2;
  rec.rows.reserve(2 * rows * (4 + 2 * rig_.metronomes.size()));
  rec.after_event.reserve(2 * rows);
  const RunReport rep = engine.run(rig_, rec);
  if (!rep.complete) throw ModelFailure(rep.failure);
  if (!rep.final_trajectory_row.empty()) rec.add(rep.final_trajectory_row, false);
  if (rec.after_event.empty()) throw ModelFailure("the model wrote no state");
  width_ = rec.width;
  events_ = std::move(rec.events);
  const std::size_t count = rec.after_event.size();
  const auto time = [&](std::size_t k) { return rec.rows[k * width_]; };
  bool sorted = true;
  for (std::size_t k = 1; k < count && sorted; ++k) sorted = !(time(k) < time(k - 1));
  if (sorted) {  // as the engine writes them but for a final row at the end
    rows_ = std::move(rec.rows);
    after_event_ = std::move(rec.after_event);
    return;
  }
  std::vector<std::size_t> order(count);
  for (std::size_t k = 0; k < count; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return time(a) < time(b); });
  rows_.reserve(rec.rows.size());
  for (std::size_t k : order) {
    rows_.insert(rows_.end(), rec.rows.begin() + k * width_, rec.rows.begin() + (k + 1) * width_);
    after_event_.push_back(rec.after_event[k]);
  }
}

double ModelTrajectory::at(double t, int metronome) const {
  const int c = columnOf(metronome);
  const std::size_t count = after_event_.size();
  // the first knot after t
  std::size_t lo = 0, hi = count;
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (t < row(mid)[0])
      hi = mid;
    else
      lo = mid + 1;
  }
  if (lo == 0) return row(0)[c];
  if (lo == count) return row(count - 1)[c];
  const double *a = row(lo - 1), *b = row(lo);
  const double h = b[0] - a[0], s = t - a[0];
  const double ya = a[c], va = a[c + 1], yb = b[c], vb = b[c + 1];
  if (!(h > 0)) return yb;
  if (after_event_[lo]) return ya + va * s + (yb - ya - va * h) * (s / h) * (s / h);
  // cubic Hermite on [a, b]
  const double u = s / h, u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * ya + (u3 - 2 * u2 + u) * h * va + (-2 * u3 + 3 * u2) * yb +
         (u3 - u2) * h * vb;
}

std::vector<double> sampleSlowFlow(const Engine& engine, Rig rig,
                                   const std::vector<SampleRequest>& requests) {
  if (requests.empty()) return {};
  const ScaledParams sp0 = computeScaled(rig);
  // one fast period past the last request, so that the envelope grid covers it
  rig.sim.t_end_s = lastTime(requests) + kTwoPi * sp0.time_scale_s;
  EnvelopeRecorder rec;
  const RunReport rep = engine.run(rig, rec);
  if (!rep.complete) throw ModelFailure(rep.failure);
  if (rec.rows.empty()) throw ModelFailure("the slow flow wrote no envelope");
  const ScaledParams sp = computeScaled(rig);
  const double tau_per_s = sp.epsilon / sp.time_scale_s;
  std::vector<double> out;
  out.reserve(requests.size());
  for (const SampleRequest& r : requests) {
    if (r.metronome < 0) throw std::invalid_argument("the slow flow has no platform position x");
    out.push_back(envelopeAt(rec.rows, r.t_s * tau_per_s, r.metronome) * sp.angle_scale);
  }
  return out;
}

}  // namespace metrosync
