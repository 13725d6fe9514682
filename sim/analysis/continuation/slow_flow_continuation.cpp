#include "sim/analysis/continuation/slow_flow_continuation.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "sim/analysis/continuation/arclength.h"
#include "sim/analysis/continuation/merge.h"
#include "sim/analysis/continuation/start_states.h"
#include "sim/analysis/continuation/state_traces.h"
#include "sim/parallel/ordered_tasks.h"

namespace metrosync::continuation {

namespace {

using Cd = std::complex<double>;
// Two seeds of one type whose parameters agree this well (relative) are one point: points are
// located to ~1e-11.
constexpr double kSameSeed = 1e-7;

// A located fold or Hopf point with the problem (reference metronome) it was found in.
struct Seed {
  std::shared_ptr<const SlowFlowProblem> prob;
  BranchPoint at;
  CurveKind kind;
};

// The branches appended to r; their folds and Hopf points to seeds.
void commit(const Traced& t, ContinuationResult& r, std::vector<Seed>& seeds) {
  appendBranches(*t.prob, t.branches, r);
  for (const Branch& b : t.branches)
    for (const Bifurcation& e : b.special) {
      if (e.type == BifurcationType::Fold && e.point.on_border < 0)
        seeds.push_back({t.prob, e.point, CurveKind::Fold});
      if (e.type == BifurcationType::Hopf) seeds.push_back({t.prob, e.point, CurveKind::Hopf});
    }
}

void fromStart(const SlowFlowContinuationSpec& spec, ContinuationResult& r,
               std::vector<Seed>& seeds) {
  const auto prob = problemFor(spec, spec.start);
  const auto x = solveLocked(*prob, prob->pack(spec.start, prob->omegaGuess(spec.from, spec.start)),
                             spec.from);
  if (!x) throw NoLockedState("Newton does not converge to a locked state from the start");
  commit(traceState(prob, *x, spec), r, seeds);
}

// Every locked state Newton finds at `from`, each followed unless a branch followed before it
// passes through it: in order, as one loop, the states followed ahead on spec.jobs threads
// (orderedTasks: the branches and their order are the sequential loop's), a copy of an earlier
// state with identical metronomes exchanged mapped from that state's branches (state_traces.h).
void fromEveryState(const SlowFlowContinuationSpec& spec, ContinuationResult& r,
                    std::vector<Seed>& seeds) {
  const ScaledParams sp = spec.params(spec.from);
  int ref = 0;
  while (ref < static_cast<int>(sp.locked.size()) && sp.locked[ref]) ++ref;
  if (ref == static_cast<int>(sp.locked.size())) throw NoLockedState("every metronome is locked");
  if (!spec.start.empty()) fromStart(spec, r, seeds);  // the rig's own state first: branch 0
  const SlowFlowProblem grid(spec.params, spec.from, ref);
  const std::vector<Vec> states = allLockedStates(grid, spec.from, spec.jobs);
  if (states.empty() && r.branches.empty()) throw NoLockedState("Newton finds no locked state");
  const double span = std::abs(spec.to - spec.from);
  StateTraces traces(spec, grid, states);
  std::vector<Traced> traced(states.size());
  orderedTasks(
      static_cast<long>(states.size()), spec.jobs,
      [&](long k) {
        return alreadyFollowed(r, spec.from, grid.amplitudes(states[k]),
                               grid.phaseDifferences(states[k]), span);
      },
      [&](long k) { traced[k] = traces.of(k); },
      [&](long k) {
        commit(traced[k], r, seeds);
        traced[k] = Traced();
      });
}

// The seeds whose point is still a special point of r (after merging), one per point.
std::vector<Seed> distinctSeeds(const std::vector<Seed>& seeds, const ContinuationResult& r) {
  std::vector<Seed> out;
  auto same = [](double a, double b) {
    return std::abs(a - b) <= kSameSeed * std::max(1.0, std::abs(a));
  };
  for (const Seed& s : seeds) {
    const char* type = s.kind == CurveKind::Fold ? "fold" : "hopf";
    const bool kept = std::any_of(r.special.begin(), r.special.end(), [&](const ResultSpecial& e) {
      return e.type == type && same(e.at.value, s.at.p());
    });
    const bool seen = std::any_of(out.begin(), out.end(), [&](const Seed& o) {
      return o.kind == s.kind && same(o.at.p(), s.at.p());
    });
    if (kept && !seen) out.push_back(s);
  }
  return out;
}

// The Hopf seed nearest p (its index in seeds), -1 when there is none.
int nearestHopf(const std::vector<Seed>& seeds, double p) {
  int best = -1;
  for (size_t k = 0; k < seeds.size(); ++k)
    if (seeds[k].kind == CurveKind::Hopf &&
        (best < 0 || std::abs(seeds[k].at.p() - p) < std::abs(seeds[best].at.p() - p)))
      best = static_cast<int>(k);
  return best;
}

// Cycles are followed for at most this many metronomes: the shooting integrates the reduced
// flow's 2N - 1 states with their (2N - 1)^2 sensitivities, so a step's cost grows as N^3 to N^4
// (a pair: ~0.6 s of CPU per cycle branch; 32 metronomes: over a minute before the first cycle,
// docs/bench/slow-continuation.md).
constexpr int kMaxCycleMetronomes = 4;

// The cycle of each Hopf seed, but for one a cycle already followed ends on (the same cycles).
void cycles(const SlowFlowContinuationSpec& spec, const std::vector<Seed>& seeds,
            ContinuationResult& r) {
  ContinuationSettings s = spec.settings;
  if (spec.cycle_points > 0) s.max_points = spec.cycle_points;
  r.cycle_budget = s.max_points;
  for (size_t k = 0; k < seeds.size(); ++k) {
    if (seeds[k].kind != CurveKind::Hopf) continue;
    if (r.metronomes > kMaxCycleMetronomes) {
      ResultCycle skipped;
      skipped.hopf_value = seeds[k].at.p();
      skipped.end = "not followed: " + std::to_string(r.metronomes) + " metronomes (cycles for " +
                    "at most " + std::to_string(kMaxCycleMetronomes) +
                    ": the shooting's cost grows as N^3 or faster)";
      r.cycles.push_back(skipped);
      r.cycles.back().id = static_cast<int>(r.cycles.size()) - 1;
      continue;
    }
    const auto joined = std::find_if(r.cycles.begin(), r.cycles.end(), [&](const ResultCycle& c) {
      return c.into_hopf && !c.points.empty() &&
             nearestHopf(seeds, c.points.back().value) == static_cast<int>(k);
    });
    if (joined != r.cycles.end()) {
      ResultCycle same;
      same.hopf_value = seeds[k].at.p();
      same.end = "not followed: the cycles of cycle " + std::to_string(joined->id) +
                 " end on this Hopf point (one family joins the two)";
      r.cycles.push_back(same);
    } else {
      r.cycles.push_back(followSlowFlowCycle(*seeds[k].prob, seeds[k].at, s));
    }
    r.cycles.back().id = static_cast<int>(r.cycles.size()) - 1;
  }
}

void curves(const SlowFlowContinuationSpec& spec, const std::vector<Seed>& seeds,
            ContinuationResult& r) {
  const double span1 = std::max(std::abs(spec.to - spec.from), 1e-300);
  const double span2 = std::max(std::abs(spec.to2 - spec.from2), 1e-300);
  for (const Seed& seed : seeds) {
    if (onACurve(r.fold_curves, seed.kind, seed.at.p(), spec.from2, span1, span2) ||
        onACurve(spec.known_curves, seed.kind, seed.at.p(), spec.from2, span1, span2))
      continue;
    const int n = static_cast<int>(seed.at.y.size()) - 1;
    const auto followCurve = seed.kind == CurveKind::Fold ? continueFold : continueHopf;
    try {
      r.fold_curves.push_back(followCurve(spec.params2, seed.prob->reference(), seed.at.y.head(n),
                                          seed.at.p(), spec.from2, seed.at.region, spec.settings2,
                                          spec.range1));
    } catch (const std::exception& e) {  // a seed the curve's Newton cannot start from
      FoldCurve failed;
      failed.kind = seed.kind;
      failed.seed_p1 = seed.at.p(), failed.seed_p2 = spec.from2;
      failed.failure = e.what();
      r.fold_curves.push_back(failed);
    }
  }
  mergeCurves(r.fold_curves, span1, span2);
}

}  // namespace

ContinuationResult continueSlowFlow(const SlowFlowContinuationSpec& spec) {
  ContinuationResult r;
  r.from = spec.from, r.to = spec.to;
  const ScaledParams sp = spec.params(spec.from);
  r.metronomes = static_cast<int>(sp.nu.size());
  r.theta_c = sp.theta_c;
  std::vector<Seed> seeds;
  if (spec.all || spec.start.empty())
    fromEveryState(spec, r, seeds);
  else
    fromStart(spec, r, seeds);
  mergeDuplicates(r);
  const std::vector<Seed> distinct = distinctSeeds(seeds, r);
  if (spec.cycles) cycles(spec, distinct, r);
  if (spec.params2) curves(spec, distinct, r);
  return r;
}

}  // namespace metrosync::continuation
