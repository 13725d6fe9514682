#include "sim/analysis/continuation/slow_flow_cycles.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sim/analysis/continuation/cycle_fold_check.h"
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

ResultCyclePoint resultPoint(const SlowFlowProblem& prob, const CyclePoint& q) {
  ResultCyclePoint r;
  r.value = q.p, r.period = q.period, r.stable = q.stable;
  r.A0 = prob.amplitudes(prob.fromPolar(q.y0));
  r.psi0 = prob.phaseDifferences(prob.fromPolar(q.y0));
  extremes(prob, q.orbit, r);
  for (const auto& m : q.multipliers) {
    r.multipliers.push_back(m);
    if (std::abs(m - 1.0) > q.trivial_error)
      r.max_multiplier = std::max(r.max_multiplier, std::abs(m));
  }
  return r;
}

// The fold f of the branch c, with the check by runs of the slow flow on its two legs (the
// branch's points on either side of the point where p turns back at f).
ResultCycleFold checkedFold(const SlowFlowProblem& prob, const CycleBranch& c,
                            const CyclePoint& f) {
  ResultCycleFold out;
  out.at = resultPoint(prob, f);
  size_t k = 0;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 1; i + 1 < c.points.size(); ++i) {
    const double turn = (c.points[i].p - c.points[i - 1].p) * (c.points[i + 1].p - c.points[i].p);
    const double d = std::abs(c.points[i].p - f.p);
    if (turn <= 0 && d < best) best = d, k = i;
  }
  if (k == 0) {
    out.check = "not confirmed: too few cycles beside it";
    return out;
  }
  auto on = [](const CyclePoint& q) { return CycleOnBranch{q.p, q.period, q.stable, q.orbit}; };
  std::vector<CycleOnBranch> a, b;
  for (size_t i = k; i-- > 0;) a.push_back(on(c.points[i]));
  for (size_t i = k + 1; i < c.points.size(); ++i) b.push_back(on(c.points[i]));
  const FoldCheck check = checkCycleFold(prob, f.p, a, b);
  out.confirmed = check.confirmed, out.check = check.check;
  return out;
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
  // how far inside the Hopf point's region: the smallest border function, signed to its side
  f.margin = [&prob, region](const Vec& y, double p) {
    const Vec b = prob.system().borders(prob.fromPolar(y), p);
    double m = std::numeric_limits<double>::infinity();
    for (int k = 0; k < b.size(); ++k) m = std::min(m, region[k] ? b(k) : -b(k));
    return m;
  };
  CycleBranch c;
  try {
    c = continueCycleFromHopf(f, prob.polarState(x), hopf.p(), s);
  } catch (const std::runtime_error& e) {
    out.end = std::string("not followed: ") + e.what();
    return out;
  }
  out.frequency = c.hopf_frequency, out.end = c.end, out.changes = c.changes;
  out.max_points = c.max_points, out.into_hopf = c.into_hopf;
  for (const CyclePoint& q : c.points) out.points.push_back(resultPoint(prob, q));
  for (const CyclePoint& q : c.folds) out.folds.push_back(checkedFold(prob, c, q));
  return out;
}

}  // namespace metrosync::continuation
