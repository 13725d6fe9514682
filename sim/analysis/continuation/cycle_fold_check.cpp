#include "sim/analysis/continuation/cycle_fold_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "sim/engines/slow_flow/slow_flow_engine.h"

namespace metrosync::continuation {

namespace {

using Cd = std::complex<double>;
// Each run lasts this many periods of the cycle; the stable cycle is judged over the last
// kTailPeriods (a start on the cycle's numerical orbit settles onto the true one well before).
constexpr double kRunPeriods = 40, kTailPeriods = 10;
// On the cycle: every state of the tail within kStays of the orbit (amplitudes, phases: the
// shooting's cycle and the slow flow's differ by ~1e-6); off it: some state farther than kLeaves
// (the drift beyond a fold takes the state to another attractor, O(0.1) or more away).
constexpr double kStays = 1e-2, kLeaves = 0.1;

// (A_1.., psi_2..) of each orbit sample.
std::vector<std::vector<double>> statesOf(const SlowFlowProblem& prob,
                                          const std::vector<Vec>& orbit) {
  std::vector<std::vector<double>> out;
  for (const Vec& y : orbit) {
    const Vec x = prob.fromPolar(y);
    std::vector<double> s = prob.amplitudes(x);
    const std::vector<double> psi = prob.phaseDifferences(x);
    s.insert(s.end(), psi.begin(), psi.end());
    out.push_back(std::move(s));
  }
  return out;
}

double toOrbit(const EnvelopeRow& row, const std::vector<std::vector<double>>& orbit) {
  double best = std::numeric_limits<double>::infinity();
  const size_t n = row.A.size();
  for (const auto& s : orbit) {
    double d = 0;
    for (size_t i = 0; i < n; ++i) d = std::max(d, std::abs(row.A[i] - s[i]));
    for (size_t j = 0; j < row.psi.size(); ++j)
      d = std::max(d, std::abs(std::remainder(row.psi[j] - s[n + j], 2 * M_PI)));
    best = std::min(best, d);
  }
  return best;
}

// The largest distance from the orbit over [tail_from, tau_end] of a run at p from z0.
double runDistance(const SlowFlowProblem& prob, double p, const std::vector<Cd>& z0,
                   const std::vector<std::vector<double>>& orbit, double tau_end,
                   double tail_from) {
  ScaledParams sp = prob.params(p);
  for (size_t i = 0; i < z0.size(); ++i)
    sp.thetadot0[i] = z0[i].real(), sp.theta0[i] = z0[i].imag();
  SlowFlowOptions opt;
  opt.tau_end = tau_end;
  MemorySink sink;
  const RunReport rep = runSlowFlow(sp, opt, sink);
  if (!rep.complete) return std::numeric_limits<double>::infinity();
  double d = 0;
  for (const EnvelopeRow& row : sink.envelope)
    if (row.tau >= tail_from) d = std::max(d, toOrbit(row, orbit));
  return d;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace

FoldCheck checkCycleFold(const SlowFlowProblem& prob, double p_f, const CycleOnBranch& before,
                         const CycleOnBranch& after) {
  const CycleOnBranch* s = before.stable ? &before : after.stable ? &after : nullptr;
  if (!s || s->orbit.empty())
    return {false,
            "not confirmed: neither cycle beside the fold is stable, so no forward run of the "
            "slow flow can stay on one"};
  const std::vector<std::vector<double>> orbit = statesOf(prob, s->orbit);
  const std::vector<Cd> z0 = prob.unpack(prob.fromPolar(s->orbit.back()));
  const double tau = kRunPeriods * s->period, p_b = 2 * p_f - s->p;
  const double on = runDistance(prob, s->p, z0, orbit, tau, tau - kTailPeriods * s->period);
  const double off = runDistance(prob, p_b, z0, orbit, tau, 0.0);
  FoldCheck c;
  c.confirmed = on < kStays && off > kLeaves;
  c.check = std::string(c.confirmed ? "confirmed" : "not confirmed") +
            " by the slow flow: a run on the stable cycle at p = " + num(s->p) + " stays within " +
            num(on) + " of it over " + num(kRunPeriods) + " periods; at p = " + num(p_b) +
            ", beyond the fold, it drifts " + num(off) + " away";
  return c;
}

}  // namespace metrosync::continuation
