#include "sim/analysis/continuation/border_states.h"

#include <cmath>
#include <cstdio>

#include "base/number_text.h"
#include "sim/analysis/continuation/derivatives.h"
#include "sim/analysis/continuation/newton.h"
#include "sim/analysis/continuation/test_functions.h"

namespace metrosync::continuation {

namespace {

// The region of sys with border k's side set.
Region withSide(const Region& r, int k, int side) {
  Region out(r.begin(), r.end() - 1);  // the border system has one more border: 1 - w
  out[k] = side;
  return out;
}

// The gradient of border k at x (central differences).
Vec borderGradient(const ContinuationSystem& sys, const Vec& x, double p, int k) {
  Vec g(x.size());
  for (int i = 0; i < x.size(); ++i) {
    const double h = centralStep(x(i));
    Vec up = x, down = x;
    up(i) += h, down(i) -= h;
    g(i) = (sys.borders(up, p)(k) - sys.borders(down, p)(k)) / (2 * h);
  }
  return g;
}

// x moved onto border k along the border function's gradient (one Newton step: exact for the
// escapement's |z_i| - theta_c). The formulas are evaluated there: the escapement's amplitude
// term goes as sqrt(|z_i| - theta_c), whose difference quotients across the border are
// meaningless and would spoil Newton; the constraint b_k = 0 fixes the normal direction.
Vec ontoBorder(const ContinuationSystem& sys, const Vec& x, double p, int k) {
  const double b = sys.borders(x, p)(k);
  const Vec g = borderGradient(sys, x, p, k);
  return g.squaredNorm() > 0 ? Vec(x - b * g / g.squaredNorm()) : x;
}

// (x, w) with parameter p; borders: those of sys with b_k replaced by w, then 1 - w (both exits:
// the branch leaves the border there). Another jump border also ends the segment.
ContinuationSystem borderSystem(const ContinuationSystem& sys, int k, int K) {
  const int n = sys.n;
  ContinuationSystem b;
  b.n = n + 1;
  b.residual = [sys, k, n](const Vec& u, double p, const Region& r) {
    const Vec x = ontoBorder(sys, u.head(n), p, k);
    const double w = u(n);
    Vec out(n + 1);
    out.head(n) =
        w * sys.residual(x, p, withSide(r, k, 1)) + (1 - w) * sys.residual(x, p, withSide(r, k, 0));
    out(n) = sys.borders(u.head(n), p)(k);
    return out;
  };
  b.borders = [sys, k, n](const Vec& u, double p) {
    const Vec bx = sys.borders(u.head(n), p);
    Vec out(bx.size() + 1);
    out << bx, 1 - u(n);
    out(k) = u(n);
    return out;
  };
  b.jumps = [sys, k, K](int j) { return j != k && j != K && sys.jumps && sys.jumps(j); };
  b.exits = [sys, k, K](int j) { return j == k || j == K || (sys.jumps && sys.jumps(j)); };
  b.eigenvalues = [](const Vec&, double, const Region&) { return CVec(); };
  b.borderName = [sys, k, K](int j) {
    return j == k ? "weight 0" : j == K ? "weight 1" : sys.borderName(j);
  };
  b.tolerance = sys.tolerance;
  return b;
}

// A point of the border system as a point of sys: on border k with its weight.
BranchPoint onBorder(const BranchPoint& q, int n, int k) {
  BranchPoint out = q;
  out.y = Vec(n + 1);
  out.y << q.y.head(n), q.y(n + 1);
  out.tangent = Vec(n + 1);
  out.tangent << q.tangent.head(n), q.tangent(n + 1);
  if (out.tangent.norm() > 0) out.tangent.normalize();
  out.region.assign(q.region.begin(), q.region.end() - 1);
  out.region[k] = kOnBorder;
  out.on_border = k;
  out.weight = q.y(n);
  out.max_real = std::numeric_limits<double>::quiet_NaN();
  return out;
}

// leave() starts the regular branch this far inside its region (in the border function's units:
// an amplitude), the first depth at which Newton converges there: far above its accuracy, small
// enough to skip nothing visible.
constexpr double kLeaveDepths[] = {1e-4, 1e-3, 1e-2};

// The start of the segment: `at` with w = its side, the tangent along which w moves into (0, 1).
BranchPoint entry(const ContinuationSystem& border, const BranchPoint& at, int k) {
  const int n = static_cast<int>(at.y.size()) - 1;
  Vec y(n + 2), ref = Vec::Zero(n + 2);
  const double w0 = at.region[k] == 1 ? 1.0 : 0.0;
  y << at.y.head(n), w0, at.p();
  ref << at.tangent.head(n), 0.0, at.tangent(n);
  Region r = at.region;
  r[k] = 1;
  r.push_back(1);
  Vec t = tangentAt(border, y, ref, r);
  if ((t(n) < 0) != (w0 == 1.0)) t = -t;  // w decreases from 1, increases from 0
  BranchPoint q;
  q.y = y, q.tangent = t, q.region = r;
  return q;
}

// Where the segment leaves the border: a regular point of sys on side `side` of border k, its
// tangent pointing away from the border. The escapement's branch meets its border tangentially
// (the amplitude term goes as sqrt(A - theta_c): A - theta_c ~ (p - p*)^2, on one side of p*
// only) and Newton has no derivative on the border itself, where it lands on the other side's
// continued formulas instead; so the branch is started where it lies kLeaveDepth inside the
// region: Newton on (F = 0, b_k = +-depth) in (x, p).
std::optional<BranchPoint> leave(const ContinuationSystem& sys, const BranchPoint& last, int k,
                                 int side) {
  const int n = sys.n;
  Region r = last.region;
  r[k] = side;
  const Vec g = borderGradient(sys, last.y.head(n), last.p(), k);
  for (const double depth : kLeaveDepths) {
    const double b = side == 1 ? depth : -depth;
    ContinuationSystem at;
    at.n = n + 1;
    at.residual = [&](const Vec& y, double, const Region&) {
      Vec out(n + 1);
      out << sys.residual(y.head(n), y(n), r), sys.borders(y.head(n), y(n))(k) - b;
      return out;
    };
    at.tolerance = sys.tolerance;
    Vec y0 = last.y;
    y0.head(n) += b * g / g.squaredNorm();
    const auto y = solveAt(at, y0, 0.0, Region{});
    if (!y || regionAt(sys, y->head(n), (*y)(n)) != r) continue;
    return makePoint(sys, *y, tangentAt(sys, *y, *y - last.y, r), r);
  }
  return std::nullopt;
}

Bifurcation borderEvent(const BranchPoint& at, int k, const std::string& detail, bool changes) {
  Bifurcation b;
  b.type = BifurcationType::Border;
  b.point = at;
  b.border = k;
  b.detail = detail;
  b.stability_changes = changes;
  return b;
}

// The stability of each border state (the system's own dynamics), and of the special points.
void judge(const ContinuationSystem& sys, std::vector<BranchPoint>& points,
           std::vector<Bifurcation>& special) {
  const int n = sys.n;
  for (BranchPoint& q : points)
    q.stable = sys.stableOnBorder && sys.stableOnBorder(q.y.head(n), q.p());
  for (Bifurcation& e : special)
    e.point.stable = sys.stableOnBorder && sys.stableOnBorder(e.point.y.head(n), e.point.p());
}

std::string stabilityWord(const ContinuationSystem& sys, bool stable) {
  if (!sys.stableOnBorder) return "stability unknown";
  return stable ? "stable" : "unstable";
}

// The segment's points and special points as states of sys on border k, judged.
void collect(const ContinuationSystem& sys, const Walk& seg, int k,
             std::vector<BranchPoint>& points, std::vector<Bifurcation>& special) {
  for (size_t i = 0; i < seg.points.size(); ++i)
    points.push_back(onBorder(seg.points[i], sys.n, k));
  for (const Bifurcation& e : seg.special) {
    Bifurcation b = e;
    b.point = onBorder(e.point, sys.n, k);
    b.detail = "border states: " + e.detail;
    special.push_back(b);
  }
  judge(sys, points, special);
}

}  // namespace

std::optional<BranchPoint> slideAlong(const ContinuationSystem& sys, const BranchPoint& at, int k,
                                      const ContinuationSettings& s, int max_points, Walk& w) {
  const int K = static_cast<int>(at.region.size());
  const ContinuationSystem border = borderSystem(sys, k, K);
  const BranchPoint e = entry(border, at, k);
  const int budget = std::max(2, max_points - static_cast<int>(w.points.size()) + 1);
  const Walk seg = walkFrom(border, makePoint(border, e.y, e.tangent, e.region), s, budget);
  std::vector<BranchPoint> points;
  std::vector<Bifurcation> special;
  collect(sys, seg, k, points, special);
  w.special.push_back(borderEvent(
      at, k,
      "boundary equilibrium at " + sys.borderName(k) + ": the branch goes on along the border " +
          "(border states: the two sides' formulas combined, weight " +
          numberText(points.front().weight, 3) + " of the upper side's); " +
          stabilityWord(sys, at.stable) + " -> " + stabilityWord(sys, points.front().stable),
      at.stable != points.front().stable));
  w.special.insert(w.special.end(), special.begin(), special.end());
  w.points.insert(w.points.end(), points.begin() + 1, points.end());
  if (seg.exit < 0 || (seg.exit != k && seg.exit != K)) {
    w.end = seg.exit < 0 ? "on the border " + sys.borderName(k) + ": " + seg.end
                         : "the border states on " + sys.borderName(k) + " meet " +
                               sys.borderName(seg.exit) + " (not followed)";
    w.end_p = seg.exit < 0 ? seg.end_p : std::numeric_limits<double>::quiet_NaN();
    w.max_points = seg.max_points;
    return std::nullopt;
  }
  const BranchPoint& last = w.points.back();
  const int side = seg.exit == K ? 1 : 0;
  const auto left = leave(sys, last, k, side);
  if (!left) {
    w.end = "the border states reach weight " + numberText(side, 3) + " on " + sys.borderName(k) +
            " but no branch of that side's formulas starts there";
    w.end_p = last.p();
    return std::nullopt;
  }
  const BranchPoint& after = *left;
  w.special.push_back(borderEvent(
      last, k,
      "the border states leave " + sys.borderName(k) + " at weight " + numberText(side, 3) +
          ": the branch goes on " + (side ? "above" : "below") + " it; " +
          stabilityWord(sys, last.stable) + " -> " + stabilityWord(sys, after.stable),
      last.stable != after.stable));
  return after;
}

}  // namespace metrosync::continuation
