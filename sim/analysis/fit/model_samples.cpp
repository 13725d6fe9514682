#include "sim/analysis/fit/model_samples.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "base/constants.h"
#include "models/scaling.h"

namespace metrosync {

namespace {

// The run goes this many rows past the last request, so that it is inside the record.
constexpr double kEndMarginRows = 2.0;

struct Knot {
  std::vector<double> row;  // trajectory format: t, x, xdot, theta_1, thetadot_1, ..., platform
  bool after_event = false;
};

struct TrajectoryRecorder : RunSink {
  std::vector<Knot> knots;
  void trajectoryRow(const std::vector<double>& row) override { knots.push_back({row, false}); }
  void eventRow(const char*, const std::vector<double>& row) override {
    knots.push_back({row, true});
  }
};

struct EnvelopeRecorder : RunSink {
  std::vector<EnvelopeRow> rows;
  void envelopeRow(const EnvelopeRow& row) override { rows.push_back(row); }
};

// The value at t of the quantity in column `c` (its rate in c + 1), interpolated between knots.
double interpolate(const std::vector<Knot>& k, double t, int c) {
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

double lastTime(const std::vector<SampleRequest>& requests) {
  double t = 0.0;
  for (const SampleRequest& r : requests) t = std::max(t, r.t_s);
  return t;
}

std::vector<double> sampleFull(const Engine& engine, Rig rig,
                               const std::vector<SampleRequest>& requests, double row_dt_s) {
  rig.sim.sample_s = row_dt_s;
  rig.sim.t_end_s = lastTime(requests) + kEndMarginRows * row_dt_s;
  TrajectoryRecorder rec;
  const RunReport rep = engine.run(rig, rec);
  if (!rep.complete) throw ModelFailure(rep.failure);
  if (!rep.final_trajectory_row.empty()) rec.knots.push_back({rep.final_trajectory_row, false});
  std::stable_sort(rec.knots.begin(), rec.knots.end(),
                   [](const Knot& a, const Knot& b) { return a.row[0] < b.row[0]; });
  std::vector<double> out;
  out.reserve(requests.size());
  for (const SampleRequest& r : requests)
    out.push_back(interpolate(rec.knots, r.t_s, r.metronome < 0 ? 1 : 3 + 2 * r.metronome));
  return out;
}

std::vector<double> sampleSlow(const Engine& engine, Rig rig,
                               const std::vector<SampleRequest>& requests) {
  const ScaledParams sp0 = computeScaled(rig);
  // one fast period past the last request, so that the envelope grid covers it
  rig.sim.t_end_s = lastTime(requests) + 2 * kPi * sp0.time_scale_s;
  EnvelopeRecorder rec;
  const RunReport rep = engine.run(rig, rec);
  if (!rep.complete) throw ModelFailure(rep.failure);
  const ScaledParams sp = computeScaled(rig);
  const double tau_per_s = sp.epsilon / sp.time_scale_s;
  std::vector<double> out;
  for (const SampleRequest& r : requests) {
    if (r.metronome < 0) throw std::invalid_argument("the slow flow has no platform position x");
    const double tau = r.t_s * tau_per_s;
    auto it = std::upper_bound(rec.rows.begin(), rec.rows.end(), tau,
                               [](double v, const EnvelopeRow& n) { return v < n.tau; });
    const std::size_t i = r.metronome;
    double A = 0.0;
    if (it == rec.rows.begin()) {
      A = rec.rows.front().A.at(i);
    } else if (it == rec.rows.end()) {
      A = rec.rows.back().A.at(i);
    } else {
      const EnvelopeRow &a = *(it - 1), &b = *it;
      const double w = b.tau > a.tau ? (tau - a.tau) / (b.tau - a.tau) : 1.0;
      A = a.A.at(i) + w * (b.A.at(i) - a.A.at(i));
    }
    out.push_back(A * sp.angle_scale);
  }
  return out;
}

}  // namespace

std::vector<double> sampleModel(const Engine& engine, Rig rig,
                                const std::vector<SampleRequest>& requests, double row_dt_s) {
  if (requests.empty()) return {};
  if (engine.model() == "slow") return sampleSlow(engine, std::move(rig), requests);
  return sampleFull(engine, std::move(rig), requests, row_dt_s);
}

}  // namespace metrosync
