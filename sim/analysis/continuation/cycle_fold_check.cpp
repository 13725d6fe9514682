#include "sim/analysis/continuation/cycle_fold_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "base/constants.h"
#include "base/number_text.h"
#include "sim/engines/slow_flow/slow_flow_engine.h"

namespace metrosync::continuation {

namespace {

using Cd = std::complex<double>;
// Each run lasts this many periods of the cycle; the stable cycle is judged over the last
// kTailPeriods (a start on the cycle's numerical orbit settles onto the true one well before).
constexpr double kRunPeriods = 40, kTailPeriods = 10;
// Beyond the fold the drift starts slowly (the cycles' ghost): the run lasts longer.
constexpr double kBeyondPeriods = 150;
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

// Distance from the row's (A, psi) to the orbit's polyline (psi unwrapped about the row's).
double toOrbit(const EnvelopeRow& row, const std::vector<std::vector<double>>& orbit) {
  const size_t n = row.A.size(), m = n + row.psi.size();
  std::vector<double> q(row.A);
  q.insert(q.end(), row.psi.begin(), row.psi.end());
  auto near = [&](const std::vector<double>& s) {
    std::vector<double> u = s;
    for (size_t j = n; j < m; ++j) u[j] = q[j] + std::remainder(s[j] - q[j], kTwoPi);
    return u;
  };
  double best = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < orbit.size(); ++k) {
    const std::vector<double> a = near(orbit[k]), b = near(orbit[(k + 1) % orbit.size()]);
    double ab2 = 0, t = 0;
    for (size_t i = 0; i < m; ++i)
      ab2 += (b[i] - a[i]) * (b[i] - a[i]), t += (q[i] - a[i]) * (b[i] - a[i]);
    t = ab2 > 0 ? std::clamp(t / ab2, 0.0, 1.0) : 0.0;
    double d = 0;
    for (size_t i = 0; i < m; ++i) d = std::max(d, std::abs(q[i] - a[i] - t * (b[i] - a[i])));
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

}  // namespace

namespace {

// The stable leg's cycle halfway along its stable stretch from the fold (null: no stable leg).
const CycleOnBranch* stableCycle(const std::vector<CycleOnBranch>& a,
                                 const std::vector<CycleOnBranch>& b) {
  for (const auto* leg : {&a, &b}) {
    size_t run = 0;
    while (run < leg->size() && (*leg)[run].stable) ++run;
    if (run > 0) return &(*leg)[run / 2];
  }
  return nullptr;
}

}  // namespace

FoldCheck checkCycleFold(const SlowFlowProblem& prob, double p_f,
                         const std::vector<CycleOnBranch>& leg_a,
                         const std::vector<CycleOnBranch>& leg_b) {
  const CycleOnBranch* s = stableCycle(leg_a, leg_b);
  if (!s || s->orbit.empty())
    return {false,
            "not confirmed: neither leg of cycles at the fold is stable, so no forward run of the "
            "slow flow can stay on one"};
  const std::vector<std::vector<double>> orbit = statesOf(prob, s->orbit);
  const std::vector<Cd> z0 = prob.unpack(prob.fromPolar(s->orbit.back()));
  const double p_b = 2 * p_f - s->p, T = s->period;
  const double on =
      runDistance(prob, s->p, z0, orbit, kRunPeriods * T, (kRunPeriods - kTailPeriods) * T);
  const double off = runDistance(prob, p_b, z0, orbit, kBeyondPeriods * T, 0.0);
  FoldCheck c;
  c.confirmed = on < kStays && off > kLeaves;
  c.check = std::string(c.confirmed ? "confirmed" : "not confirmed") +
            " by the slow flow: a run on the stable cycle at p = " + numberText(s->p, 3) +
            " stays within " + numberText(on, 3) + " of it over " + numberText(kRunPeriods, 3) +
            " periods; at p = " + numberText(p_b, 3) + ", beyond the fold, it drifts " +
            numberText(off, 3) + " away within " + numberText(kBeyondPeriods, 3) + " periods";
  return c;
}

}  // namespace metrosync::continuation
