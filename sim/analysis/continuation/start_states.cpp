#include "sim/analysis/continuation/start_states.h"

#include <atomic>
#include <cmath>
#include <exception>

#include "base/constants.h"
#include "base/number_text.h"
#include "sim/analysis/continuation/family.h"
#include "sim/analysis/continuation/newton.h"
#include "sim/engines/slow_flow/slow_flow_engine.h"
#include "sim/parallel/worker_pool.h"

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
// Up to this many metronomes every combination of seeds (4^N levels x 2^(N-1) phases: 256 at
// N = 3); above, symmetric patterns only (patterns()).
constexpr int kFullGridUpTo = 3;
// A start this close to a border (in its function: amplitude, |Z|) may belong to either side.
constexpr double kNearBorder = 1e-2;

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
  return "amplitudes still vary by " + numberText(dA, 3) + " and phase differences by " +
         numberText(dpsi, 3);
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

namespace {

// A solution of region's formulas from x0 that lies in region, or a member of a neutral family
// there moved inside it; nullopt otherwise (`found` then holds what Newton found, if anything).
std::optional<Vec> solveIn(const SlowFlowProblem& prob, const Vec& x0, double p,
                           const Region& region, std::optional<Vec>& found) {
  const ContinuationSystem& sys = prob.system();
  found = solveAt(sys, x0, p, region);
  if (!found) return std::nullopt;
  if (regionAt(sys, *found, p) == region) return found;
  const auto nd = neutralDirections(sys, *found, p, region);
  return nd ? memberInside(sys, *nd, *found, p, region) : std::nullopt;
}

}  // namespace

std::optional<Vec> solveLocked(const SlowFlowProblem& prob, const Vec& x0, double p) {
  const ContinuationSystem& sys = prob.system();
  Region region = regionAt(sys, x0, p);
  Vec x = x0;
  for (int it = 0; it < kMaxRegionChanges; ++it) {
    std::optional<Vec> found;
    std::optional<Vec> sol = solveIn(prob, x, p, region, found);
    // a start within kNearBorder of a border (a run that stops where the platform sticks): the
    // other side's formulas too
    const Vec b = sys.borders(x, p);
    for (int k = 0; !sol && !found && k < b.size(); ++k) {
      if (std::abs(b(k)) > kNearBorder) continue;
      Region other = region;
      other[k] = 1 - other[k];
      sol = solveIn(prob, x, p, other, found);
      if (!sol && found) region = other;
    }
    if (sol) return prob.pack(prob.unpack(*sol), prob.omega(*sol));
    if (!found) return std::nullopt;
    region = regionAt(sys, *found, p);
    x = *found;
  }
  return std::nullopt;
}

namespace {

using StartSeed = std::pair<std::vector<double>, std::vector<double>>;  // (A, psi)

// Every combination of the levels (each metronome) and phase differences: levels^N phases^(N-1).
std::vector<StartSeed> fullGrid(int n, const std::vector<double>& levels,
                                const std::vector<double>& phases) {
  long combos = 1;
  for (int i = 0; i < n; ++i) combos *= static_cast<long>(levels.size());
  for (int j = 1; j < n; ++j) combos *= static_cast<long>(phases.size());
  std::vector<StartSeed> seeds;
  for (long c = 0; c < combos; ++c) {
    long r = c;
    StartSeed s{std::vector<double>(n), std::vector<double>(n - 1)};
    for (int i = 0; i < n; ++i, r /= static_cast<long>(levels.size()))
      s.first[i] = levels[r % levels.size()];
    for (int j = 1; j < n; ++j, r /= static_cast<long>(phases.size()))
      s.second[j - 1] = phases[r % phases.size()];
    seeds.push_back(s);
  }
  return seeds;
}

// For many metronomes (the full grid grows as 8^N): the symmetric patterns only, each at every
// level -- in phase, two clusters in antiphase, splay, one metronome against the rest -- and each
// metronome suppressed (the lowest level) with the others at every level in phase.
std::vector<StartSeed> patterns(int n, const std::vector<double>& levels) {
  std::vector<std::vector<double>> phase_sets(4, std::vector<double>(n - 1, 0.0));
  for (int j = 1; j < n; ++j) {
    phase_sets[1][j - 1] = j % 2 ? kPi : 0.0;  // alternating clusters
    phase_sets[2][j - 1] = -2 * kPi * j / n;   // splay
  }
  phase_sets[3][n - 2] = kPi;  // the last one against the rest
  std::vector<StartSeed> seeds;
  for (double level : levels)
    for (const auto& psi : phase_sets) seeds.push_back({std::vector<double>(n, level), psi});
  for (int i = 0; i < n; ++i)
    for (double level : levels) {
      StartSeed s{std::vector<double>(n, level), std::vector<double>(n - 1, 0.0)};
      s.first[i] = levels.front();
      seeds.push_back(s);
    }
  return seeds;
}

}  // namespace

std::vector<Vec> allLockedStates(const SlowFlowProblem& prob, double p, int jobs) {
  const ScaledParams& sp = prob.params(p);
  const int n = prob.metronomes();
  double tc = 0, astar = 0;
  for (int i = 0; i < n; ++i) {
    tc = std::max(tc, sp.theta_c[i]);
    if (sp.A_star[i]) astar = std::max(astar, *sp.A_star[i]);
  }
  if (astar == 0) astar = 2 * tc + 1;
  const std::vector<double> levels = {0.3 * tc, 1.2 * tc, astar, 1.4 * astar};
  const std::vector<double> phases =
      n <= 2 ? std::vector<double>{0, kPi / 2, kPi, 3 * kPi / 2} : std::vector<double>{0, kPi};
  const std::vector<StartSeed> seeds =
      n <= kFullGridUpTo ? fullGrid(n, levels, phases) : patterns(n, levels);
  // each seed solved on its own (a problem per thread: its cache is not shared), the first
  // failure in the seeds' order rethrown as the loop over them would have
  std::vector<std::optional<Vec>> solved(seeds.size());
  std::vector<std::exception_ptr> failed(seeds.size());
  auto solve = [&](const SlowFlowProblem& mine, size_t k) {
    StartSeed seed = seeds[k];
    for (int i = 0; i < n; ++i)
      if (sp.locked[i]) seed.first[i] = 0;
    const std::vector<Cd> z = stateFrom(seed.first, seed.second);
    if (std::abs(z[mine.reference()]) == 0) return;
    solved[k] = solveLocked(mine, mine.pack(z, mine.omegaGuess(p, z)), p);
  };
  std::atomic<size_t> next{0};
  runWorkers(workerCount(jobs, static_cast<long>(seeds.size())), [&] {
    const SlowFlowProblem mine(prob);
    for (size_t k; (k = next++) < seeds.size();) {
      try {
        solve(mine, k);
      } catch (...) {
        failed[k] = std::current_exception();
      }
    }
  });
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
  std::vector<Vec> found;
  for (const std::optional<Vec>& x : solved) {
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
