#include "sim/analysis/continuation/fold_curve.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>

#include "sim/analysis/continuation/arclength.h"
#include "sim/analysis/continuation/bialternate.h"
#include "sim/analysis/continuation/derivatives.h"

namespace metrosync::continuation {

namespace {

// The curve system's acceptance level: g's difference Jacobian has errors ~1e-10 and the outer
// Newton differentiates it again, so 1e-9 is what it reaches reliably.
constexpr double kFoldTolerance = 1e-9;
// A Hopf pair whose imaginary part falls below this (relative to the largest eigenvalue) has
// turned real: the curve has passed a Bogdanov-Takens point. Far above the ~1e-9 noise of the
// difference Jacobian, far below the frequencies of the slow flow's Hopf points (~0.1-3).
constexpr double kRealPair = 1e-6;
// A curve whose last point is this close to an edge of p1's range (relative to the range) was
// stopped by it: the arclength steps near the edge shrink to ~1e-9 before the corrector gives up.
constexpr double kRangeEdge = 1e-3;

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

// The bordered matrix [M b; c^T 0] and its solution's last component g.
double borderedFunction(const Mat& S, const Vec& b, const Vec& c) {
  const int n = static_cast<int>(S.rows());
  Mat M = Mat::Zero(n + 1, n + 1);
  M.topLeftCorner(n, n) = S;
  M.col(n).head(n) = b;
  M.row(n).head(n) = c.transpose();
  Vec rhs = Vec::Zero(n + 1);
  rhs(n) = 1.0;
  return M.fullPivLu().solve(rhs)(n);
}

// The matrix that is singular on the curve: F_x (fold) or 2A (.) I (Hopf).
Mat singularMatrix(CurveKind kind, const SlowFlowProblem& prob, const Vec& x, double p1,
                   const Region& region) {
  if (kind == CurveKind::Fold) return jacobianX(prob.system(), x, p1, region);
  return bialternateProduct(prob.reducedJacobian(x, p1, region));
}

// Hopf: w of the eigenvalue pair nearest the imaginary axis (0 when that pair is real).
double hopfFrequency(const SlowFlowProblem& prob, const Vec& x, double p1, const Region& region) {
  const CVec ev = prob.reducedJacobian(x, p1, region).eigenvalues();
  if (ev.size() == 0) return 0.0;
  Eigen::Index k = 0;
  ev.real().cwiseAbs().minCoeff(&k);
  const double scale = std::max(1.0, ev.cwiseAbs().maxCoeff());
  return std::abs(ev(k).imag()) > kRealPair * scale ? std::abs(ev(k).imag()) : 0.0;
}

FoldCurve continueCurve(CurveKind kind, const ParamsAt2& params, int reference, const Vec& x0,
                        double p1_0, double p2_0, const Region& region,
                        const ContinuationSettings& s, P1Range range);

}  // namespace

const char* toString(CurveKind k) {
  return k == CurveKind::Fold ? "fold" : "hopf";
}

FoldCurve continueFold(const ParamsAt2& params, int reference, const Vec& x0, double p1_0,
                       double p2_0, const Region& region, const ContinuationSettings& s,
                       P1Range range) {
  return continueCurve(CurveKind::Fold, params, reference, x0, p1_0, p2_0, region, s, range);
}

FoldCurve continueHopf(const ParamsAt2& params, int reference, const Vec& x0, double p1_0,
                       double p2_0, const Region& region, const ContinuationSettings& s,
                       P1Range range) {
  return continueCurve(CurveKind::Hopf, params, reference, x0, p1_0, p2_0, region, s, range);
}

namespace {

FoldCurve continueCurve(CurveKind kind, const ParamsAt2& params, int reference, const Vec& x0,
                        double p1_0, double p2_0, const Region& region,
                        const ContinuationSettings& s, P1Range range) {
  auto family = std::make_shared<Family>(params, p1_0, reference);
  const int n = family->at(p2_0).system().n;
  // the null vectors of the singular matrix at the starting point
  const Mat S0 = singularMatrix(kind, family->at(p2_0), x0, p1_0, region);
  Eigen::JacobiSVD<Mat> svd(S0, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const int k = static_cast<int>(S0.rows());
  const Vec b = svd.matrixU().col(k - 1), c = svd.matrixV().col(k - 1);

  ContinuationSystem sys;
  sys.n = n + 1;  // (x, p1)
  // the start's region held throughout (no borders: the curve is cut where it leaves the region)
  sys.residual = [family, b, c, n, region, kind, range](const Vec& y, double p2, const Region&) {
    const SlowFlowProblem& prob = family->at(p2);
    const Vec x = y.head(n);
    Vec out(n + 1);
    // outside p1's range the corrector fails, so the step control stops the curve at its edge
    if (y(n) < range.lo || y(n) > range.hi) return Vec(Vec::Constant(n + 1, std::nan("")));
    out.head(n) = prob.system().residual(x, y(n), region);
    out(n) = borderedFunction(singularMatrix(kind, prob, x, y(n), region), b, c);
    return out;
  };
  sys.eigenvalues = [](const Vec&, double, const Region&) { return CVec(); };
  // g comes from a difference Jacobian (~1e-10 noise, derivatives.h): solve to well above it
  sys.tolerance = kFoldTolerance;

  Vec y0(n + 1);
  y0 << x0, p1_0;
  FoldCurve curve;
  curve.kind = kind;
  ContinuationSettings inner = s;
  inner.max_branches = 1;
  const std::vector<Branch> branches = continueFrom(sys, y0, p2_0, inner);
  curve.end_backward = branches.at(0).end_backward;
  curve.end_forward = branches[0].end_forward;
  // the points inside the region, from the start outwards both ways
  const auto& pts = branches[0].points;
  auto inside = [&](const BranchPoint& q) {
    const SlowFlowProblem& prob = family->at(q.p());
    if (regionAt(prob.system(), q.y.head(n), q.y(n)) != region) return false;
    return kind == CurveKind::Fold || hopfFrequency(prob, q.y.head(n), q.y(n), region) > 0;
  };
  size_t start = 0;
  while (start < pts.size() && pts[start].p() != p2_0) ++start;
  size_t lo = start, hi = start;
  while (lo > 0 && inside(pts[lo - 1])) --lo;
  while (hi + 1 < pts.size() && inside(pts[hi + 1])) ++hi;
  auto why = [&](const BranchPoint& q) {
    const SlowFlowProblem& prob = family->at(q.p());
    if (q.y(n) <= range.lo || q.y(n) >= range.hi)
      return std::string("leaves the first key's range");
    if (regionAt(prob.system(), q.y.head(n), q.y(n)) != region)
      return std::string("leaves the start's region (a border of the vector field)");
    return std::string(
        "the pair +-i w turns real (a Bogdanov-Takens point; beyond it a neutral saddle)");
  };
  if (lo > 0) curve.end_backward = why(pts[lo - 1]);
  if (hi + 1 < pts.size()) curve.end_forward = why(pts[hi + 1]);
  for (size_t q = lo; q <= hi && q < pts.size(); ++q) {
    const SlowFlowProblem& prob = family->at(pts[q].p());
    const Vec x = pts[q].y.head(n);
    const double w = kind == CurveKind::Hopf ? hopfFrequency(prob, x, pts[q].y(n), region) : 0.0;
    curve.points.push_back(
        {pts[q].y(n), pts[q].p(), prob.amplitudes(x), prob.phaseDifferences(x), w});
  }
  // an end stopped by p1's range (the corrector fails just past it) says so
  const double edge = kRangeEdge * (range.hi - range.lo);
  auto atEdge = [&](const FoldCurvePoint& q) {
    return std::isfinite(edge) && (q.p1 - range.lo < edge || range.hi - q.p1 < edge);
  };
  if (!curve.points.empty() && atEdge(curve.points.front()))
    curve.end_backward = "reaches the edge of the first key's range";
  if (!curve.points.empty() && atEdge(curve.points.back()))
    curve.end_forward = "reaches the edge of the first key's range";
  return curve;
}

}  // namespace

}  // namespace metrosync::continuation
