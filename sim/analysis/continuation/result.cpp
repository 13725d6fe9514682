#include "sim/analysis/continuation/result.h"

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
  r.ticking = prob.ticking(q.region);
  r.platform = prob.platform(q.region);
  r.s = prob.s(x, q.p());
  for (int i = 0; i < q.eigenvalues.size(); ++i) r.eigenvalues.push_back(q.eigenvalues(i));
  return r;
}

}  // namespace

void appendBranches(const SlowFlowProblem& prob, const std::vector<Branch>& branches,
                    ContinuationResult& out) {
  const int offset = static_cast<int>(out.branches.size());
  for (const Branch& b : branches) {
    const int id = offset + b.id;
    out.branches.push_back({id, static_cast<long>(b.points.size()), b.end_backward, b.end_forward});
    for (const BranchPoint& q : b.points) out.points.push_back(resultPoint(prob, q, id));
    for (const Bifurcation& e : b.special)
      out.special.push_back({resultPoint(prob, e.point, id), toString(e.type), e.detail, e.lyapunov,
                             e.stability_changes});
  }
}

}  // namespace metrosync::continuation
