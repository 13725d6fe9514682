#include "sim/analysis/continuation/result.h"

#include <algorithm>
#include <cmath>

#include "base/constants.h"

namespace metrosync::continuation {

namespace {

ResultPoint resultPoint(const SlowFlowProblem& prob, const BranchPoint& q, int branch) {
  const Vec x = q.y.head(prob.system().n);
  ResultPoint r;
  r.branch = branch;
  r.value = q.p();
  r.A = prob.amplitudes(x);
  r.psi = prob.phaseDifferences(x);
  r.omega = prob.omega(x);
  r.stable = q.stable;
  r.max_real = q.max_real;
  r.ticking = prob.ticking(q.region, q.weight);
  r.platform = prob.platform(q.region);
  r.s = prob.s(x, q.p());
  if (!std::isfinite(r.s)) r.s = std::nan("");  // mu = 0: no threshold, no value
  for (int i = 0; i < q.eigenvalues.size(); ++i) r.eigenvalues.push_back(q.eigenvalues(i));
  if (q.on_border >= 0) {
    r.on_threshold = prob.metronomeOf(q.on_border) + 1;
    r.weight = q.weight;
  }
  return r;
}

// The range of A_i and psi_j over a family's members, psi unwrapped about the first
// representative's (the members run continuously from one end to the other).
ResultFamilyPoint familyPoint(const SlowFlowProblem& prob, const BranchPoint& rep,
                              const FamilyExtent& e) {
  ResultFamilyPoint f;
  f.value = rep.p();
  f.closed = e.closed;
  f.ends = e.ends;
  const std::vector<double> psi0 = prob.phaseDifferences(rep.y.head(prob.system().n));
  for (const Vec& x : e.members) {
    const std::vector<double> A = prob.amplitudes(x);
    std::vector<double> psi = prob.phaseDifferences(x);
    for (size_t j = 0; j < psi.size(); ++j)
      psi[j] = psi0[j] + std::remainder(psi[j] - psi0[j], kTwoPi);
    if (f.A_min.empty()) f.A_min = f.A_max = A, f.psi_min = f.psi_max = psi;
    for (size_t i = 0; i < A.size(); ++i)
      f.A_min[i] = std::min(f.A_min[i], A[i]), f.A_max[i] = std::max(f.A_max[i], A[i]);
    for (size_t j = 0; j < psi.size(); ++j)
      f.psi_min[j] = std::min(f.psi_min[j], psi[j]), f.psi_max[j] = std::max(f.psi_max[j], psi[j]);
  }
  return f;
}

}  // namespace

void appendBranches(const SlowFlowProblem& prob, const std::vector<Branch>& branches,
                    ContinuationResult& out) {
  const int offset = static_cast<int>(out.branches.size());
  for (const Branch& b : branches) {
    const int id = offset + b.id;
    ResultBranch rb{id, static_cast<long>(b.points.size()), b.end_backward, b.end_forward};
    rb.max_points = b.max_points_backward || b.max_points_forward;
    rb.neutral = b.neutral;
    out.branches.push_back(rb);
    for (const BranchPoint& q : b.points) out.points.push_back(resultPoint(prob, q, id));
    for (const Bifurcation& e : b.special)
      out.special.push_back({resultPoint(prob, e.point, id), toString(e.type), e.detail, e.lyapunov,
                             e.stability_changes});
    if (b.neutral == 0) continue;
    ResultFamily f;
    f.id = static_cast<int>(out.families.size());
    f.branch = id;
    f.neutral = b.neutral;
    f.cause = prob.familyCause(b.points.front().region, b.neutral);
    for (size_t i = 0; i < b.points.size() && i < b.extent.size(); ++i)
      f.points.push_back(familyPoint(prob, b.points[i], b.extent[i]));
    out.families.push_back(std::move(f));
  }
}

}  // namespace metrosync::continuation
