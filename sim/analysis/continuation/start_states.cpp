#include "sim/analysis/continuation/start_states.h"

#include <cmath>

#include "base/constants.h"
#include "sim/analysis/continuation/newton.h"
#include "sim/engines/slow_flow/slow_flow_engine.h"

namespace metrosync::continuation {

namespace {

using Cd = std::complex<double>;
// A run is settled when over its last fifth amplitudes and phase differences stay within this of
// their final values: a locked state is constant, a slow drift or modulation is far larger.
constexpr double kSettleTolerance = 1e-4;
// A slow approach (near a fold) may need longer than the rig's own run: tau_end times these.
constexpr double kSettleHorizons[] = {1.0, 3.0, 10.0};
// A state with every amplitude below this is the state at rest (its Omega is undetermined).
constexpr double kRestAmplitude = 1e-6;
// Two solutions closer than this (in x) are one.
constexpr double kSameSolution = 1e-6;
// Region re-solves before a seed is dropped: each moves the solution across at least one border.
constexpr int kMaxRegionChanges = 4;

double wrapped(double d) {
  return std::remainder(d, 2 * kPi);
}

std::string drift(const std::vector<EnvelopeRow>& rows, size_t from) {
  const EnvelopeRow& last = rows.back();
  double dA = 0, dpsi = 0;
  for (size_t r = from; r < rows.size(); ++r) {
    for (size_t i = 0; i < last.A.size(); ++i)
      dA = std::max(dA, std::abs(rows[r].A[i] - last.A[i]));
    for (size_t j = 0; j < last.psi.size(); ++j)
      dpsi = std::max(dpsi, std::abs(wrapped(rows[r].psi[j] - last.psi[j])));
  }
  if (dA <= kSettleTolerance && dpsi <= kSettleTolerance) return "";
  char buf[160];
  std::snprintf(buf, sizeof buf, "amplitudes still vary by %.3g and phase differences by %.3g", dA,
                dpsi);
  return buf;
}

}  // namespace

std::vector<Cd> stateFrom(const std::vector<double>& A, const std::vector<double>& psi) {
  std::vector<Cd> z;
  for (size_t i = 0; i < A.size(); ++i)
    z.push_back(i == 0 ? Cd(A[0]) : std::polar(A[i], -psi[i - 1]));
  return z;
}

SettledState settleFromStart(const ScaledParams& sp, double tau_end) {
  SettledState st;
  for (double factor : kSettleHorizons) {
    st = settleOver(sp, factor * tau_end);
    if (st.settled || st.z.empty()) return st;
  }
  return st;
}

SettledState settleOver(const ScaledParams& sp, double tau_end) {
  SlowFlowOptions opt;
  opt.tau_end = tau_end;
  MemorySink sink;
  const RunReport rep = runSlowFlow(sp, opt, sink);
  SettledState st;
  st.tau = tau_end;
  if (!rep.complete) {
    st.why = "the slow flow failed: " + rep.failure;
    return st;
  }
  if (sink.envelope.size() < 10) {
    st.why = "the run is too short to tell (" + std::to_string(sink.envelope.size()) + " rows)";
    return st;
  }
  const EnvelopeRow& last = sink.envelope.back();
  double amax = 0;
  for (double a : last.A) amax = std::max(amax, a);
  if (amax < kRestAmplitude) {
    st.why = "every metronome stops (the state at rest: nothing to continue)";
    return st;
  }
  st.why = drift(sink.envelope, sink.envelope.size() * 4 / 5);
  st.settled = st.why.empty();
  if (!st.settled) st.why += " over the last fifth of the run";
  st.z = stateFrom(last.A, last.psi);
  return st;
}

std::optional<Vec> solveLocked(const SlowFlowProblem& prob, const Vec& x0, double p) {
  const ContinuationSystem& sys = prob.system();
  Region region = regionAt(sys, x0, p);
  Vec x = x0;
  for (int it = 0; it < kMaxRegionChanges; ++it) {
    const auto sol = solveAt(sys, x, p, region);
    if (!sol) return std::nullopt;
    const Region there = regionAt(sys, *sol, p);
    if (there == region) return prob.pack(prob.unpack(*sol), prob.omega(*sol));
    region = there;
    x = *sol;
  }
  return std::nullopt;
}

std::vector<Vec> allLockedStates(const SlowFlowProblem& prob, double p) {
  const ScaledParams& sp = prob.params(p);
  const int n = prob.metronomes();
  std::vector<double> levels;  // amplitude seeds, shared by all metronomes
  double tc = 0, astar = 0;
  for (int i = 0; i < n; ++i) {
    tc = std::max(tc, sp.theta_c[i]);
    if (sp.A_star[i]) astar = std::max(astar, *sp.A_star[i]);
  }
  if (astar == 0) astar = 2 * tc + 1;
  levels = {0.3 * tc, 1.2 * tc, astar, 1.4 * astar};
  const std::vector<double> phases =
      n <= 2 ? std::vector<double>{0, kPi / 2, kPi, 3 * kPi / 2} : std::vector<double>{0, kPi};
  long combos = 1;
  for (int i = 0; i < n; ++i) combos *= static_cast<long>(levels.size());
  for (int j = 1; j < n; ++j) combos *= static_cast<long>(phases.size());
  std::vector<Vec> found;
  for (long c = 0; c < combos; ++c) {
    long r = c;
    std::vector<double> A(n), psi(n > 1 ? n - 1 : 0);
    for (int i = 0; i < n; ++i, r /= levels.size())
      A[i] = sp.locked[i] ? 0 : levels[r % levels.size()];
    for (int j = 1; j < n; ++j, r /= phases.size()) psi[j - 1] = phases[r % phases.size()];
    const std::vector<Cd> z = stateFrom(A, psi);
    if (std::abs(z[prob.reference()]) == 0) continue;
    const auto x = solveLocked(prob, prob.pack(z, prob.omegaGuess(p, z)), p);
    if (!x) continue;
    double amax = 0;
    for (double a : prob.amplitudes(*x)) amax = std::max(amax, a);
    bool dup = amax < kRestAmplitude;
    for (const Vec& f : found) dup = dup || (f - *x).norm() < kSameSolution;
    if (!dup) found.push_back(*x);
  }
  return found;
}

}  // namespace metrosync::continuation
