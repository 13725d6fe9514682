#include "sim/analysis/continuation/test_functions.h"

#include <cmath>

#include "sim/analysis/continuation/arclength.h"
#include "sim/analysis/continuation/newton.h"

namespace metrosync::continuation {

namespace {

// Location stops when the bracket in arclength is this narrow: near a fold p varies as h^2, so
// the parameter is then exact to far better than the required 1e-8; elsewhere the point is on
// the branch to ~1e-11.
constexpr double kLocateArclength = 1e-11;
constexpr int kMaxLocateIterations = 100;

}  // namespace

double foldTest(const BranchPoint& q) {
  return q.tangent(q.tangent.size() - 1);
}

namespace {

// det [E; t^T], E = [F_x F_p] at the point.
double branchTestOf(const Mat& extended, const Vec& t) {
  const Eigen::Index n = extended.rows();
  Mat M(n + 1, n + 1);
  M.topRows(n) = extended;
  M.row(n) = t.transpose();
  return M.determinant();
}

}  // namespace

double branchTest(const ContinuationSystem& sys, const BranchPoint& q) {
  const auto& known = q.branch_test;
  if (known && known->y == q.y && known->tangent == q.tangent && known->region == q.region)
    return known->value;
  return branchTestOf(extendedJacobian(sys, q.y, q.region), q.tangent);
}

// Re prod_{i<j} (lambda_i + lambda_j) without forming the product, whose 1953 factors for 32
// metronomes under- or overflow a double: its modulus as the geometric mean of the factors'
// moduli (the M-th root keeps the sign and the zeros, and stays continuous), times the cosine of
// the summed arguments.
double hopfTest(const CVec& ev) {
  double log_modulus = 0.0, argument = 0.0;
  int factors = 0;
  for (int i = 0; i < ev.size(); ++i)
    for (int j = i + 1; j < ev.size(); ++j) {
      const std::complex<double> s = ev(i) + ev(j);
      if (s == 0.0) return 0.0;
      log_modulus += std::log(std::abs(s));
      argument += std::arg(s);
      ++factors;
    }
  if (factors == 0) return 1.0;
  return std::exp(log_modulus / factors) * std::cos(argument);
}

std::optional<BranchPoint> pointAlong(const ContinuationSystem& sys, const BranchPoint& from,
                                      double h, int* iterations) {
  const auto c = correct(sys, from.y, from.tangent, h, from.region);
  if (!c) return std::nullopt;
  if (iterations) *iterations = c->iterations;
  // an expensive Jacobian (multiple shooting): the corrector's last one gives the tangent (its
  // error, O(the last Newton step), is far below what the predictor needs)
  if (sys.jacobian && c->extended.size() > 0)
    return makePoint(sys, c->y, tangentOf(c->extended, from.tangent), from.region);
  // else the Jacobian at the point gives the tangent and the branch test (smoothEvents asks for
  // it at both ends of each step)
  const Mat extended = extendedJacobian(sys, c->y, from.region);
  const Vec t = tangentOf(extended, from.tangent);
  BranchPoint q = makePoint(sys, c->y, t, from.region);
  if (sys.special_points && sys.branch_points)
    q.branch_test = std::make_shared<const BranchPoint::BranchTestValue>(
        BranchPoint::BranchTestValue{q.y, q.tangent, q.region, branchTestOf(extended, t)});
  return q;
}

std::optional<BranchPoint> locateOnStep(const ContinuationSystem& sys, const BranchPoint& from,
                                        double h1, double g0, double g1,
                                        const std::function<double(const BranchPoint&)>& g,
                                        double* h_found) {
  double a = 0.0, b = h1, ga = g0, gb = g1;
  std::optional<BranchPoint> best;
  int side = 0;  // Illinois: halve the weight of an end kept twice in a row
  for (int it = 0; it < kMaxLocateIterations && b - a > kLocateArclength; ++it) {
    double h = (a * gb - b * ga) / (gb - ga);
    if (!(h > a && h < b)) h = 0.5 * (a + b);
    const auto q = pointAlong(sys, from, h);
    if (!q) return std::nullopt;
    const double gh = g(*q);
    best = q;
    if (h_found) *h_found = h;
    if (gh == 0.0) break;
    if ((gh > 0) == (ga > 0)) {
      a = h, ga = gh;
      if (side == -1) gb *= 0.5;
      side = -1;
    } else {
      b = h, gb = gh;
      if (side == 1) ga *= 0.5;
      side = 1;
    }
  }
  return best;
}

}  // namespace metrosync::continuation
