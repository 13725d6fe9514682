#include "sim/analysis/continuation/slow_flow_cycles.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sim/analysis/continuation/limit_cycle.h"

namespace metrosync::continuation {

namespace {

// The orbit's extremes of A_i and psi_j, from its polar states.
void extremes(const SlowFlowProblem& prob, const std::vector<Vec>& orbit, ResultCyclePoint& out) {
  for (const Vec& y : orbit) {
    const Vec x = prob.fromPolar(y);
    const std::vector<double> A = prob.amplitudes(x), psi = prob.phaseDifferences(x);
    if (out.A_min.empty()) out.A_min = out.A_max = A, out.psi_min = out.psi_max = psi;
    for (size_t i = 0; i < A.size(); ++i)
      out.A_min[i] = std::min(out.A_min[i], A[i]), out.A_max[i] = std::max(out.A_max[i], A[i]);
    for (size_t j = 0; j < psi.size(); ++j)
      out.psi_min[j] = std::min(out.psi_min[j], psi[j]),
      out.psi_max[j] = std::max(out.psi_max[j], psi[j]);
  }
}

}  // namespace

ResultCycle followSlowFlowCycle(const SlowFlowProblem& prob, const BranchPoint& hopf,
                                const ContinuationSettings& s) {
  const int n = prob.system().n;
  const Vec x = hopf.y.head(n);
  ResultCycle out;
  out.hopf_value = hopf.p();
  for (double a : prob.amplitudes(x))
    if (a == 0) {
      out.end = "not followed: an amplitude is 0 at the Hopf point (the polar flow is singular)";
      return out;
    }
  const Region region = hopf.region;
  CycleField f;
  f.n = n - 1;
  // parameters the rig refuses (NaN, slowFlowRhs throws) give NaN rates: the corrector fails there
  // and the step control stays out
  f.rhs = [&prob, region](const Vec& y, double p) -> Vec {
    try {
      return prob.polarRates(y, p, region);
    } catch (const std::invalid_argument&) {
      return Vec::Constant(y.size(), std::numeric_limits<double>::quiet_NaN());
    }
  };
  f.inside = [&prob, region](const Vec& y, double p) {
    return regionAt(prob.system(), prob.fromPolar(y), p) == region;
  };
  CycleBranch c;
  try {
    c = continueCycleFromHopf(f, prob.polarState(x), hopf.p(), s);
  } catch (const std::runtime_error& e) {
    out.end = std::string("not followed: ") + e.what();
    return out;
  }
  out.frequency = c.hopf_frequency, out.end = c.end, out.changes = c.changes;
  for (const CyclePoint& q : c.points) {
    ResultCyclePoint r;
    r.value = q.p, r.period = q.period, r.stable = q.stable;
    r.A0 = prob.amplitudes(prob.fromPolar(q.y0));
    r.psi0 = prob.phaseDifferences(prob.fromPolar(q.y0));
    std::vector<Vec> orbit;
    flowMap(f, q.y0, q.period, q.p, kCycleSteps, &orbit);
    extremes(prob, orbit, r);
    for (const auto& m : q.multipliers) {
      r.multipliers.push_back(m);
      if (std::abs(m - 1.0) > q.trivial_error)
        r.max_multiplier = std::max(r.max_multiplier, std::abs(m));
    }
    out.points.push_back(std::move(r));
  }
  return out;
}

}  // namespace metrosync::continuation
