#include "sim/analysis/continuation/family.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/analysis/continuation/arclength.h"
#include "sim/analysis/continuation/derivatives.h"
#include "sim/analysis/continuation/newton.h"

namespace metrosync::continuation {

namespace {

// A singular value of F_x below this (relative to the largest) is a neutral direction: far above
// the difference Jacobian's noise (~1e-10), far below a regular point's smallest (1e-3 near a
// fold located to 1e-8).
constexpr double kNeutral = 1e-7;
// The confirming member lies this far along the null direction (a fold or branch point, singular
// at one point only, has no solution there).
constexpr double kProbe = 1e-2;
// memberInside looks this far along the neutral direction (the state's units: amplitudes O(1)).
constexpr double kReach = 0.5;
// A solution of the unfolded system is a member when |l| is below this multiple of the tolerance.
constexpr double kMemberLevel = 10.0;
// W^T F_p above this (relative to |F_p|): the family does not persist when p changes.
constexpr double kPersists = 1e-6;
// The trace along the family: steps in the state's units (O(1)), a range in c never reached (the
// borders or the loop end it).
constexpr double kTraceStep = 0.02, kTraceStepMax = 0.2, kTraceRange = 100.0;
constexpr int kTracePoints = 400;
// Natural-parameter steps in p: grown by kGrow, halved on failure down to kMinStep of the first.
constexpr double kGrow = 1.5, kMinStep = 1e-6;

// The k right and left singular vectors of F_x of its smallest singular values.
NeutralDirections nullVectors(const ContinuationSystem& sys, const Vec& x, double p,
                              const Region& region, int k) {
  Eigen::JacobiSVD<Mat> svd(jacobianX(sys, x, p, region),
                            Eigen::ComputeFullU | Eigen::ComputeFullV);
  return {svd.matrixV().rightCols(k), svd.matrixU().rightCols(k)};
}

// F(x, p) + W l = 0, V^T (x - x_r) = c e_1 in the unknowns (x, l), at fixed p, with c the
// continuation parameter; every border of sys ends a walk.
ContinuationSystem unfolded(const ContinuationSystem& sys, const NeutralDirections& nd,
                            const Vec& xr, double p, const Region& region) {
  const int n = sys.n, k = static_cast<int>(nd.V.cols());
  ContinuationSystem u;
  u.n = n + k;
  u.residual = [sys, nd, xr, p, region, n, k](const Vec& y, double c, const Region&) {
    Vec out(n + k);
    out.head(n) = sys.residual(y.head(n), p, region) + nd.W * y.tail(k);
    out.tail(k) = nd.V.transpose() * (y.head(n) - xr);
    out(n) -= c;
    return out;
  };
  if (sys.borders)
    u.borders = [sys, p, n](const Vec& y, double) { return sys.borders(y.head(n), p); };
  u.exits = [](int) { return true; };
  u.eigenvalues = [](const Vec&, double, const Region&) { return CVec(); };
  u.tolerance = sys.tolerance;
  u.special_points = false;  // its walks trace the members only
  return u;
}

// The member at p nearest x (c = 0 about x), when it is one (and lies in the region).
std::optional<Vec> memberAt(const ContinuationSystem& sys, const NeutralDirections& nd,
                            const Vec& x, double p, const Region& region, bool in_region = true) {
  const int n = sys.n, k = static_cast<int>(nd.V.cols());
  Vec y0 = Vec::Zero(n + k);
  y0.head(n) = x;
  const auto y = solveAt(unfolded(sys, nd, x, p, region), y0, 0.0, Region{});
  if (!y || y->tail(k).norm() > kMemberLevel * sys.tolerance) return std::nullopt;
  if (in_region && sys.borders && regionAt(sys, y->head(n), p) != region) return std::nullopt;
  return Vec(y->head(n));
}

FamilyExtent trace(const ContinuationSystem& sys, const NeutralDirections& nd, const Vec& x,
                   double p, const Region& region) {
  const int n = sys.n, k = static_cast<int>(nd.V.cols());
  const ContinuationSystem u = unfolded(sys, nd, x, p, region);
  ContinuationSettings s;
  s.p_min = -kTraceRange, s.p_max = kTraceRange;
  s.step = kTraceStep, s.step_max = kTraceStepMax;
  Vec y = Vec::Zero(n + k + 1), ref = Vec::Zero(n + k + 1);
  y.head(n) = x;
  ref(n + k) = 1.0;
  const Region r = regionAt(u, y.head(n + k), 0.0);
  const BranchPoint start = makePoint(u, y, tangentAt(u, y, ref, r), r);
  BranchPoint back = start;
  back.tangent = -start.tangent;
  const Walk fwd = walkFrom(u, start, s, kTracePoints), bwd = walkFrom(u, back, s, kTracePoints);
  FamilyExtent e;
  for (auto it = bwd.points.rbegin(); it != bwd.points.rend(); ++it)
    e.members.push_back(it->y.head(n));
  for (size_t i = 1; i < fwd.points.size(); ++i) e.members.push_back(fwd.points[i].y.head(n));
  e.closed = fwd.end.rfind("closed loop", 0) == 0 || bwd.end.rfind("closed loop", 0) == 0;
  auto why = [&](const Walk& w) {
    return w.exit >= 0 && sys.borderName ? sys.borderName(w.exit) : w.end;
  };
  e.ends = e.closed ? "none: the family closes on itself" : why(bwd) + " | " + why(fwd);
  return e;
}

// The member halfway along the extent (by distance).
Vec middle(const FamilyExtent& e) {
  std::vector<double> d(1, 0.0);
  for (size_t i = 1; i < e.members.size(); ++i)
    d.push_back(d.back() + (e.members[i] - e.members[i - 1]).norm());
  const auto it = std::lower_bound(d.begin(), d.end(), 0.5 * d.back());
  return e.members[static_cast<size_t>(it - d.begin())];
}

// The point of the family at (x, p): its stability without the k neutral eigenvalues.
BranchPoint familyPoint(const ContinuationSystem& sys, const Vec& x, double p, double dir,
                        const Region& region, int k) {
  Vec y(sys.n + 1), t = Vec::Zero(sys.n + 1);
  y << x, p;
  t(sys.n) = dir;
  BranchPoint q = makePoint(sys, y, t, region);
  std::vector<std::complex<double>> ev(q.eigenvalues.data(),
                                       q.eigenvalues.data() + q.eigenvalues.size());
  std::sort(ev.begin(), ev.end(), [](auto a, auto b) { return std::abs(a) < std::abs(b); });
  q.max_real = -std::numeric_limits<double>::infinity();
  for (size_t i = static_cast<size_t>(k); i < ev.size(); ++i)
    q.max_real = std::max(q.max_real, ev[i].real());
  q.stable = q.max_real < 0;
  return q;
}

struct FamilyWalk {
  std::vector<BranchPoint> points;
  std::vector<FamilyExtent> extent;
  std::string end;
  double end_p = std::numeric_limits<double>::quiet_NaN();
};

FamilyWalk walkFamily(const ContinuationSystem& sys, Vec x, double p, const Region& region, int k,
                      double dir, const ContinuationSettings& s) {
  FamilyWalk w;
  double dp = s.step;
  while (static_cast<int>(w.points.size()) < s.max_points) {
    const double target = dir > 0 ? std::min(p + dp, s.p_max) : std::max(p - dp, s.p_min);
    if (target == p) {
      w.end = "reached the end of the range", w.end_p = p;
      return w;
    }
    const auto m = memberAt(sys, nullVectors(sys, x, p, region, k), x, target, region);
    if (!m) {
      dp *= 0.5;
      if (dp < kMinStep * s.step) {
        w.end = "the family ends (no member in its region beyond)", w.end_p = p;
        return w;
      }
      continue;
    }
    FamilyExtent e = trace(sys, nullVectors(sys, *m, target, region, k), *m, target, region);
    x = middle(e), p = target;
    w.points.push_back(familyPoint(sys, x, p, dir, region, k));
    w.extent.push_back(std::move(e));
    dp = std::min(dp * kGrow, s.step_max);
  }
  w.end = "max points reached (" + std::to_string(s.max_points) + " per direction)", w.end_p = p;
  return w;
}

}  // namespace

std::optional<Vec> memberInside(const ContinuationSystem& sys, const NeutralDirections& nd,
                                const Vec& x, double p, const Region& region) {
  if (!sys.borders || regionAt(sys, x, p) == region) return x;
  for (double c = kProbe; c <= kReach; c *= 2)
    for (double sign : {1.0, -1.0})
      if (const auto m = memberAt(sys, nd, x + sign * c * nd.V.col(0), p, region)) return m;
  return std::nullopt;
}

std::optional<NeutralDirections> neutralDirections(const ContinuationSystem& sys, const Vec& x,
                                                   double p, const Region& region) {
  Eigen::JacobiSVD<Mat> svd(jacobianX(sys, x, p, region));
  const Vec sv = svd.singularValues();
  if (sv.size() == 0 || !sv.allFinite()) return std::nullopt;
  int k = 0;
  while (k < sv.size() && sv(sv.size() - 1 - k) < kNeutral * sv(0)) ++k;
  if (k == 0) return std::nullopt;
  const NeutralDirections nd = nullVectors(sys, x, p, region, k);
  // a second member at distance kProbe along v: a continuum, not an isolated singular point
  const auto other = memberAt(sys, nd, x + kProbe * nd.V.col(0), p, region, false);
  if (!other || (*other - x).norm() < 0.5 * kProbe) return std::nullopt;
  return nd;
}

Branch followFamily(const ContinuationSystem& sys, const Vec& x0, double p0, const Region& region,
                    const NeutralDirections& nd, const ContinuationSettings& s) {
  const int k = static_cast<int>(nd.V.cols());
  Branch b;
  b.neutral = k;
  FamilyExtent e0 = trace(sys, nd, x0, p0, region);
  const Vec x = middle(e0);
  const Vec Fp = derivativeP(sys, x, p0, region);
  const bool persists = (nd.W.transpose() * Fp).norm() <= kPersists * Fp.norm();
  FamilyWalk fwd, back;
  if (persists) {
    fwd = walkFamily(sys, x, p0, region, k, 1.0, s);
    back = walkFamily(sys, x, p0, region, k, -1.0, s);
  } else {
    fwd.end = back.end =
        "the family exists at one parameter value only (its neutral direction is not one of the "
        "parameter's change)";
    fwd.end_p = back.end_p = p0;
  }
  for (size_t i = back.points.size(); i-- > 0;) {
    BranchPoint q = back.points[i];
    q.tangent = -q.tangent;
    b.points.push_back(q), b.extent.push_back(back.extent[i]);
  }
  b.points.push_back(familyPoint(sys, x, p0, 1.0, region, k));
  b.extent.push_back(std::move(e0));
  b.points.insert(b.points.end(), fwd.points.begin(), fwd.points.end());
  b.extent.insert(b.extent.end(), fwd.extent.begin(), fwd.extent.end());
  b.end_backward = back.end, b.end_forward = fwd.end;
  b.end_p_backward = back.end_p, b.end_p_forward = fwd.end_p;
  return b;
}

}  // namespace metrosync::continuation
