#include "sim/analysis/continuation/fold_curve.h"

#include <map>
#include <memory>
#include <stdexcept>

#include "sim/analysis/continuation/arclength.h"
#include "sim/analysis/continuation/derivatives.h"

namespace metrosync::continuation {

namespace {

// The fold system's acceptance level: g's difference Jacobian has errors ~1e-10 and the outer
// Newton differentiates it again, so 1e-9 is what it reaches reliably.
constexpr double kFoldTolerance = 1e-9;

// One SlowFlowProblem (in p1) per value of p2, kept while the continuation needs it.
class Family {
 public:
  Family(ParamsAt2 params, double p1, int reference)
      : params_(std::move(params)), p1_(p1), ref_(reference) {}
  const SlowFlowProblem& at(double p2) const {
    auto it = cache_.find(p2);
    if (it != cache_.end()) return *it->second;
    if (cache_.size() > kCacheSize) cache_.clear();
    const ParamsAt2 params = params_;
    auto prob = std::make_unique<SlowFlowProblem>(
        [params, p2](double p1) { return params(p1, p2); }, p1_, ref_);
    return *cache_.emplace(p2, std::move(prob)).first->second;
  }

 private:
  static constexpr size_t kCacheSize = 64;  // a step and its differences use a handful
  ParamsAt2 params_;
  double p1_;
  int ref_;
  mutable std::map<double, std::unique_ptr<SlowFlowProblem>> cache_;
};

// The bordered matrix [F_x b; c^T 0] and its solution's last component g.
double foldFunction(const Mat& Fx, const Vec& b, const Vec& c) {
  const int n = static_cast<int>(Fx.rows());
  Mat M = Mat::Zero(n + 1, n + 1);
  M.topLeftCorner(n, n) = Fx;
  M.col(n).head(n) = b;
  M.row(n).head(n) = c.transpose();
  Vec rhs = Vec::Zero(n + 1);
  rhs(n) = 1.0;
  return M.fullPivLu().solve(rhs)(n);
}

}  // namespace

FoldCurve continueFold(const ParamsAt2& params, int reference, const Vec& x0, double p1_0,
                       double p2_0, const Region& region, const ContinuationSettings& s) {
  auto family = std::make_shared<Family>(params, p1_0, reference);
  const ContinuationSystem& base = family->at(p2_0).system();
  const int n = base.n;
  // the null vectors of F_x at the starting fold
  const Mat Fx0 = jacobianX(base, x0, p1_0, region);
  Eigen::JacobiSVD<Mat> svd(Fx0, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Vec b = svd.matrixU().col(n - 1), c = svd.matrixV().col(n - 1);

  ContinuationSystem sys;
  sys.n = n + 1;  // (x, p1)
  // the fold's region held throughout (no borders: the curve is cut where it leaves the region)
  sys.residual = [family, b, c, n, region](const Vec& y, double p2, const Region&) {
    const ContinuationSystem& f = family->at(p2).system();
    const Vec x = y.head(n);
    Vec out(n + 1);
    out.head(n) = f.residual(x, y(n), region);
    out(n) = foldFunction(jacobianX(f, x, y(n), region), b, c);
    return out;
  };
  sys.eigenvalues = [](const Vec&, double, const Region&) { return CVec(); };
  // g comes from a difference Jacobian (~1e-10 noise, derivatives.h): solve to well above it
  sys.tolerance = kFoldTolerance;

  Vec y0(n + 1);
  y0 << x0, p1_0;
  FoldCurve curve;
  ContinuationSettings inner = s;
  inner.max_branches = 1;
  const std::vector<Branch> branches = continueFrom(sys, y0, p2_0, inner);
  curve.end_backward = branches.at(0).end_backward;
  curve.end_forward = branches[0].end_forward;
  // the points inside the region, from the start outwards both ways
  const auto& pts = branches[0].points;
  auto inside = [&](const BranchPoint& q) {
    return regionAt(family->at(q.p()).system(), q.y.head(n), q.y(n)) == region;
  };
  size_t start = 0;
  while (start < pts.size() && pts[start].p() != p2_0) ++start;
  size_t lo = start, hi = start;
  while (lo > 0 && inside(pts[lo - 1])) --lo;
  while (hi + 1 < pts.size() && inside(pts[hi + 1])) ++hi;
  if (lo > 0) curve.end_backward = "leaves the fold's region (a border of the vector field)";
  if (hi + 1 < pts.size())
    curve.end_forward = "leaves the fold's region (a border of the vector field)";
  for (size_t k = lo; k <= hi && k < pts.size(); ++k) {
    const SlowFlowProblem& prob = family->at(pts[k].p());
    const Vec x = pts[k].y.head(n);
    curve.points.push_back({pts[k].y(n), pts[k].p(), prob.amplitudes(x), prob.phaseDifferences(x)});
  }
  return curve;
}

}  // namespace metrosync::continuation
