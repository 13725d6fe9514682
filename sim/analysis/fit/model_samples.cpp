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

}  // namespace

ModelTrajectory::ModelTrajectory(const Engine& engine, Rig rig, double t_end_s, double row_dt_s) {
  struct Recorder : RunSink {
    std::vector<Knot>* knots;
    void trajectoryRow(const std::vector<double>& row) override { knots->push_back({row, false}); }
    void eventRow(const char*, const std::vector<double>& row) override {
      knots->push_back({row, true});
    }
  } rec;
  rec.knots = &knots_;
  rig.sim.sample_s = row_dt_s;
  rig.sim.t_end_s = t_end_s + kEndMarginRows * row_dt_s;
  const RunReport rep = engine.run(rig, rec);
  if (!rep.complete) throw ModelFailure(rep.failure);
  if (!rep.final_trajectory_row.empty()) knots_.push_back({rep.final_trajectory_row, false});
  std::stable_sort(knots_.begin(), knots_.end(),
                   [](const Knot& a, const Knot& b) { return a.row[0] < b.row[0]; });
  if (knots_.empty()) throw ModelFailure("the model wrote no state");
}

double ModelTrajectory::at(double t, int metronome) const {
  const int c = columnOf(metronome);
  const std::vector<Knot>& k = knots_;
  auto it =
      std::upper_bound(k.begin(), k.end(), t, [](double v, const Knot& n) { return v < n.row[0]; });
  if (it == k.begin()) return k.front().row[c];
  if (it == k.end()) return k.back().row[c];
  const Knot &a = *(it - 1), &b = *it;
  const double h = b.row[0] - a.row[0], s = t - a.row[0];
  const double ya = a.row[c], va = a.row[c + 1], yb = b.row[c], vb = b.row[c + 1];
  if (!(h > 0)) return yb;
  if (b.after_event) return ya + va * s + (yb - ya - va * h) * (s / h) * (s / h);
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
