#include "sim/analysis/continuation/arclength.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "base/number_text.h"
#include "sim/analysis/continuation/borders.h"
#include "sim/analysis/continuation/family.h"
#include "sim/analysis/continuation/newton.h"
#include "sim/analysis/continuation/parameter_scale.h"
#include "sim/analysis/continuation/smooth_events.h"
#include "sim/analysis/continuation/test_functions.h"

namespace metrosync::continuation {

namespace {

// Step control: grow after an easy corrector (<= kEasyIterations), halve after a failure, give
// up below kMinStepFraction of the first step (a singular point the corrector cannot pass).
constexpr double kStepGrow = 1.5;
constexpr int kEasyIterations = 4;
constexpr double kMinStepFraction = 1e-7;
// A step whose tangent turns by more than ~25 degrees (cos < 0.9) is redone at half the length:
// a larger turn means the step cut a corner (across a tight fold, or onto a nearby branch), which
// is what makes a branch zig-zag. Below kTurnCheckFraction of the first step every turn is
// accepted (a true corner, e.g. at a border, must not stop the branch).
constexpr double kMaxTurnCos = 0.9;
constexpr double kTurnCheckFraction = 1e-3;
// The range's end is landed on by Newton at p = bound; the landing is accepted when it lies
// within this fraction of its arclength from the predictor (farther: another part of the branch,
// e.g. past a fold before the bound).
constexpr double kLandDistance = 0.5;
// A branch that creeps towards a jump border (steps below kCreepFraction of the first, within
// kNearBorder of it) is landed on it by Newton (boundaryEquilibrium).
constexpr double kCreepFraction = 1e-2;
constexpr double kNearBorder = 1e-2;
constexpr size_t kCreepRetry = 20;  // points before another try after a failed one
// A walk whose accepted steps stay below kCrawlFraction of the first for kCrawlPoints points is
// stuck at a singular point (the corrector converges only at tiny steps): it ends there instead
// of spending its point budget.
constexpr double kCrawlFraction = 1e-3;
constexpr int kCrawlPoints = 25;

// The earliest event that ends the step early: the parameter leaving its range, or a border.
struct Truncation {
  BranchPoint point;
  double h = 0.0;
  int border = -1;  // -1: the end of the parameter range
};

std::optional<Truncation> truncation(const ContinuationSystem& sys, const BranchPoint& from,
                                     const BranchPoint& to, double h,
                                     const ContinuationSettings& s) {
  std::optional<Truncation> first;
  auto consider = [&](double g0, double g1, const std::function<double(const BranchPoint&)>& g,
                      int border) {
    if ((g0 > 0) == (g1 > 0) || g1 == 0.0) return;
    double hf = h;
    const auto q = locateOnStep(sys, from, h, g0, g1, g, &hf);
    if (q && (!first || hf < first->h)) first = Truncation{*q, hf, border};
  };
  // the range: only when the step leaves it (from may lie on a bound: the start, or a restart)
  for (const double bound : {s.p_min, s.p_max}) {
    const double inside = bound == s.p_min ? 1.0 : -1.0;  // the sign of p - bound inside
    auto g = [bound](const BranchPoint& q) { return q.p() - bound; };
    if (g(to) * inside < 0) consider(inside * std::max(std::abs(g(from)), 1e-300), g(to), g, -1);
  }
  const Region there = regionAt(sys, to.y.head(sys.n), to.p());
  for (size_t k = 0; k < there.size(); ++k) {
    if (there[k] == from.region[k] || from.region[k] == kOnBorder) continue;
    auto g = [&sys, k](const BranchPoint& q) {
      return sys.borders(q.y.head(sys.n), q.p())(static_cast<int>(k));
    };
    // from lies on its region's side (or on the border itself, just switched)
    const double g0 = from.region[k] ? std::abs(g(from)) : -std::abs(g(from));
    consider(g0 == 0.0 ? (from.region[k] ? 1e-300 : -1e-300) : g0, g(to), g, static_cast<int>(k));
  }
  return first;
}

// The point of the branch at p = bound exactly, near `near` (Newton at fixed p from it).
std::optional<BranchPoint> atBound(const ContinuationSystem& sys, const BranchPoint& near,
                                   double bound) {
  const auto x = solveAt(sys, near.y.head(sys.n), bound, near.region);
  if (!x) return std::nullopt;
  Vec y(sys.n + 1);
  y << *x, bound;
  return makePoint(sys, y, tangentAt(sys, y, near.tangent, near.region), near.region);
}

// A step from cur: the point reached and its arclength, at_end when it is the range's end.
struct Stepped {
  BranchPoint point;
  double h = 0.0;
  bool at_end = false;
};

// The range's end when the tangent reaches it within h: Newton at p = bound from the predictor.
std::optional<Stepped> landing(const ContinuationSystem& sys, const BranchPoint& cur, double h,
                               const ContinuationSettings& s) {
  const double tp = cur.tangent(sys.n);
  if (tp == 0.0) return std::nullopt;
  const double bound = tp > 0 ? s.p_max : s.p_min;
  const double hb = (bound - cur.p()) / tp;
  if (!(hb >= 0 && hb <= h)) return std::nullopt;
  if (hb == 0.0) return Stepped{cur, 0.0, true};
  BranchPoint pred = cur;
  pred.y = cur.y + hb * cur.tangent;
  const auto q = atBound(sys, pred, bound);
  if (!q || (q->y - pred.y).norm() > kLandDistance * hb + 1e-12 ||
      (q->tangent(sys.n) > 0) != (tp > 0))
    return std::nullopt;
  return Stepped{*q, hb, true};
}

std::optional<Stepped> stepFrom(const ContinuationSystem& sys, const BranchPoint& cur, double h,
                                const ContinuationSettings& s, int* iterations) {
  *iterations = kEasyIterations + 1;  // a landing does not grow the step
  if (auto end = landing(sys, cur, h, s)) return end;
  const auto next = pointAlong(sys, cur, h, iterations);
  if (!next) return std::nullopt;
  if (h > kTurnCheckFraction * s.step && next->tangent.dot(cur.tangent) < kMaxTurnCos)
    return std::nullopt;
  return Stepped{*next, h, false};
}

// The boundary equilibrium near cur on jump border k: Newton on (F = 0, b_k = 0) in (x, p), the
// region held. A branch of the escapement's formulas meets its border tangentially (the amplitude
// term goes as sqrt(A - theta_c), whose derivative is infinite there), so the steps shrink as it
// creeps towards the border; this lands on the border directly.
std::optional<BranchPoint> boundaryEquilibrium(const ContinuationSystem& sys,
                                               const BranchPoint& cur, int k) {
  const int n = sys.n;
  ContinuationSystem both;
  both.n = n + 1;
  both.residual = [&sys, &cur, k, n](const Vec& y, double, const Region&) {
    Vec out(n + 1);
    out << sys.residual(y.head(n), y(n), cur.region), sys.borders(y.head(n), y(n))(k);
    return out;
  };
  both.tolerance = sys.tolerance;
  const auto y = solveAt(both, cur.y, 0.0, Region{});
  if (!y || ((*y - cur.y).norm() > kNearBorder)) return std::nullopt;
  return makePoint(sys, *y, tangentAt(sys, *y, cur.tangent, cur.region), cur.region);
}

// A jump border cur creeps towards (|b_k| < kNearBorder, the steps below kCreepFraction of the
// first step), and the boundary equilibrium on it.
std::optional<Truncation> creepingOnto(const ContinuationSystem& sys, const BranchPoint& cur,
                                       double h, const ContinuationSettings& s) {
  if (!sys.jumps || !sys.borders || h >= kCreepFraction * s.step) return std::nullopt;
  const Vec b = sys.borders(cur.y.head(sys.n), cur.p());
  for (int k = 0; k < b.size(); ++k) {
    if (!sys.jumps(k) || cur.region[k] == kOnBorder || std::abs(b(k)) > kNearBorder) continue;
    if (const auto q = boundaryEquilibrium(sys, cur, k)) return Truncation{*q, 0.0, k};
  }
  return std::nullopt;
}

void reachedEnd(const ContinuationSystem& sys, const ContinuationSettings& s, Walk& w) {
  BranchPoint& last = w.points.back();
  const double bound =
      std::abs(last.p() - s.p_min) < std::abs(last.p() - s.p_max) ? s.p_min : s.p_max;
  if (last.p() != bound)
    if (const auto q = atBound(sys, last, bound)) last = *q;  // exactly on it, not 1e-300 off
  w.end = "reached the end of the range";
  w.end_p = last.p();
}

Branch joinWalks(int id, const Walk& back, const Walk& fwd) {
  Branch b;
  b.id = id;
  for (auto it = back.points.rbegin(); it != back.points.rend(); ++it) {
    BranchPoint q = *it;
    q.tangent = -q.tangent;
    b.points.push_back(q);
  }
  b.points.insert(b.points.end(), fwd.points.begin() + 1, fwd.points.end());
  b.special = back.special;
  b.special.insert(b.special.end(), fwd.special.begin(), fwd.special.end());
  b.end_backward = back.end;
  b.end_forward = fwd.end;
  b.max_points_backward = back.max_points;
  b.max_points_forward = fwd.max_points;
  b.end_p_backward = back.end_p;
  b.end_p_forward = fwd.end_p;
  return b;
}

Branch followBothWays(const ContinuationSystem& sys, const BranchPoint& start, int id,
                      const ContinuationSettings& s, std::vector<BranchSwitch>& switches) {
  BranchPoint reverse = start;
  reverse.tangent = -start.tangent;
  const Walk fwd = walkFrom(sys, start, s, s.max_points);
  const Walk back = walkFrom(sys, reverse, s, s.max_points);
  switches.insert(switches.end(), fwd.switches.begin(), fwd.switches.end());
  switches.insert(switches.end(), back.switches.begin(), back.switches.end());
  return joinWalks(id, back, fwd);
}

std::vector<Branch> continueUnscaled(const ContinuationSystem& sys, const Vec& x0, double p0,
                                     const ContinuationSettings& s) {
  const Region region = regionAt(sys, x0, p0);
  const auto x = solveAt(sys, x0, p0, region);
  if (!x)
    throw std::runtime_error("Newton does not converge at the start, p = " + numberText(p0, 10));
  if (const auto nd = neutralDirections(sys, *x, p0, region))
    return {followFamily(sys, *x, p0, region, *nd, s)};
  Vec y(sys.n + 1);
  y << *x, p0;
  Vec ref = Vec::Zero(sys.n + 1);
  ref(sys.n) = 1.0;  // first along increasing p
  std::vector<Branch> branches;
  std::vector<BranchSwitch> switches;
  branches.push_back(followBothWays(sys, makePoint(sys, y, tangentAt(sys, y, ref, region), region),
                                    0, s, switches));
  std::vector<Vec> done;  // branch points already switched at
  for (size_t i = 0; i < switches.size() && static_cast<int>(branches.size()) < s.max_branches;
       ++i) {
    bool seen = false;
    for (const Vec& d : done) seen = seen || (d - switches[i].at.y).norm() < 1e-6;
    if (seen) continue;
    done.push_back(switches[i].at.y);
    const auto start = switchBranch(sys, switches[i], s.step);
    if (!start) continue;
    branches.push_back(followBothWays(sys, *start, static_cast<int>(branches.size()), s, switches));
  }
  return branches;
}

}  // namespace

BranchPoint makePoint(const ContinuationSystem& sys, const Vec& y, const Vec& tangent,
                      const Region& region) {
  BranchPoint q;
  q.y = y;
  q.tangent = tangent;
  q.region = region;
  q.eigenvalues = sys.eigenvalues(y.head(sys.n), y(sys.n), region);
  q.max_real = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < q.eigenvalues.size(); ++i)
    q.max_real = std::max(q.max_real, q.eigenvalues(i).real());
  q.stable = q.max_real < 0.0;
  return q;
}

Walk walkFrom(const ContinuationSystem& sys, const BranchPoint& start,
              const ContinuationSettings& s, int max_points) {
  Walk w;
  w.points.push_back(start);
  BranchPoint cur = start;
  double h = s.step;
  // creepingOnto is tried from this point on (not again right after a failure, nor where the
  // branch has just left a border)
  size_t next_try = 0;
  int crawl = 0;  // consecutive steps below kCrawlFraction of the first
  while (static_cast<int>(w.points.size()) < max_points) {
    if (w.points.size() >= next_try) {
      if (const auto c = creepingOnto(sys, cur, h, s)) {
        w.points.push_back(c->point);
        const auto after = crossBorder(sys, c->point, c->border, s, max_points, w);
        if (!after) return w;
        cur = *after;
        h = s.step;
        next_try = w.points.size() + kCreepRetry;
        continue;
      }
      if (h < kCreepFraction * s.step) next_try = w.points.size() + kCreepRetry;
    }
    int iterations = 0;
    const auto st = stepFrom(sys, cur, h, s, &iterations);
    if (!st) {
      h *= 0.5;
      if (h < kMinStepFraction * s.step) {
        w.end = "the corrector failed (arclength step " + numberText(h, 10) + ")";
        w.end_p = cur.p();
        return w;
      }
      continue;
    }
    if (st->h == 0.0) {  // the walk starts on the range's end, heading out
      reachedEnd(sys, s, w);
      return w;
    }
    if (sys.stop) {
      const std::string why = sys.stop(cur.y, st->point.y);
      if (!why.empty()) {
        w.end = why, w.end_p = cur.p();
        return w;
      }
    }
    const auto cut = truncation(sys, cur, st->point, st->h, s);
    const BranchPoint& reached = cut ? cut->point : st->point;
    if (sys.special_points)
      smoothEvents(sys, cur, reached, cut ? cut->h : st->h, w.special, w.switches);
    w.points.push_back(reached);
    if ((cut && cut->border < 0) || (!cut && st->at_end)) {
      reachedEnd(sys, s, w);
      return w;
    }
    if (cut) {
      if (sys.exits && sys.exits(cut->border)) {
        w.exit = cut->border;
        w.end = "left across border " + std::to_string(cut->border);
        return w;
      }
      const auto after = crossBorder(sys, reached, cut->border, s, max_points, w);
      if (!after) return w;  // crossBorder said why
      cur = *after;
      next_try = w.points.size() + kCreepRetry;
      if ((cur.y - w.points.back().y).norm() > 0) w.points.push_back(cur);
      continue;
    }
    if (w.points.size() > 10 && (st->point.y - start.y).norm() < 0.5 * h) {
      w.end = "closed loop: back at the start";
      return w;
    }
    cur = st->point;
    if (sys.accepted) sys.accepted(cur.y);
    crawl = h < kCrawlFraction * s.step ? crawl + 1 : 0;
    if (crawl > kCrawlPoints) {
      w.end = "the steps stay below " + numberText(kCrawlFraction, 10) +
              " of the first (a singular point the continuation cannot pass)";
      w.end_p = cur.p();
      return w;
    }
    if (iterations <= kEasyIterations) h = std::min(h * kStepGrow, s.step_max);
  }
  w.max_points = true;
  w.end = "max points reached (" + std::to_string(max_points) + " per direction)";
  w.end_p = cur.p();
  return w;
}

std::vector<Branch> continueFrom(const ContinuationSystem& sys, const Vec& x0, double p0,
                                 const ContinuationSettings& s) {
  std::vector<Branch> branches;
  if (s.p_scale == 1.0) {
    branches = continueUnscaled(sys, x0, p0, s);
  } else {
    const ParameterScale scale(p0, s);
    branches = continueUnscaled(scale.system(sys), x0, 0.0, scale.settings(s));
    for (Branch& b : branches) scale.restore(b);
  }
  for (Branch& b : branches) {  // the parameter where an end stopped, in the caller's p
    if (!std::isnan(b.end_p_backward))
      b.end_backward += " at p = " + numberText(b.end_p_backward, 10);
    if (!std::isnan(b.end_p_forward)) b.end_forward += " at p = " + numberText(b.end_p_forward, 10);
  }
  return branches;
}

}  // namespace metrosync::continuation
