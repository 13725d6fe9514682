#include "sim/analysis/continuation/arclength.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "base/number_text.h"
#include "sim/analysis/continuation/borders.h"
#include "sim/analysis/continuation/newton.h"
#include "sim/analysis/continuation/smooth_events.h"
#include "sim/analysis/continuation/test_functions.h"

namespace metrosync::continuation {

namespace {

// Step control: grow after an easy corrector (<= kEasyIterations), halve after a failure, give
// up below kMinStepFraction of the first step (a singular point the corrector cannot pass).
constexpr double kStepGrow = 1.5;
constexpr int kEasyIterations = 4;
constexpr double kMinStepFraction = 1e-7;

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
    if (there[k] == from.region[k]) continue;
    auto g = [&sys, k](const BranchPoint& q) {
      return sys.borders(q.y.head(sys.n), q.p())(static_cast<int>(k));
    };
    // from lies on its region's side (or on the border itself, just switched)
    const double g0 = from.region[k] ? std::abs(g(from)) : -std::abs(g(from));
    consider(g0 == 0.0 ? (from.region[k] ? 1e-300 : -1e-300) : g0, g(to), g, static_cast<int>(k));
  }
  return first;
}

// One direction of a branch from `start` (its tangent oriented along the direction).
struct Walk {
  std::vector<BranchPoint> points;
  std::vector<Bifurcation> special;
  std::vector<BranchSwitch> switches;
  std::string end;
};

Walk walk(const ContinuationSystem& sys, const BranchPoint& start, const ContinuationSettings& s) {
  Walk w;
  w.points.push_back(start);
  BranchPoint cur = start;
  double h = s.step;
  while (static_cast<int>(w.points.size()) < s.max_points) {
    int iterations = 0;
    const auto next = pointAlong(sys, cur, h, &iterations);
    if (!next) {
      h *= 0.5;
      if (h < kMinStepFraction * s.step) {
        w.end = "the corrector failed at step " + numberText(h, 10) +
                " after p = " + numberText(cur.p(), 10);
        return w;
      }
      continue;
    }
    const auto cut = truncation(sys, cur, *next, h, s);
    const BranchPoint& reached = cut ? cut->point : *next;
    smoothEvents(sys, cur, reached, cut ? cut->h : h, w.special, w.switches);
    w.points.push_back(reached);
    if (cut && cut->border < 0) {
      w.end = "reached the end of the range, p = " + numberText(reached.p(), 10);
      return w;
    }
    if (cut) {
      const auto after = crossBorder(sys, reached, cut->border, w.special);
      if (!after) {
        w.end = w.special.back().detail;
        return w;
      }
      cur = *after;
      if ((cur.y - reached.y).norm() > 0) w.points.push_back(cur);
      continue;
    }
    if (w.points.size() > 10 && (next->y - start.y).norm() < 0.5 * h) {
      w.end = "closed loop: back at the start";
      return w;
    }
    cur = *next;
    if (iterations <= kEasyIterations) h = std::min(h * kStepGrow, s.step_max);
  }
  w.end = "max points reached at p = " + numberText(cur.p(), 10);
  return w;
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
  return b;
}

Branch followBothWays(const ContinuationSystem& sys, const BranchPoint& start, int id,
                      const ContinuationSettings& s, std::vector<BranchSwitch>& switches) {
  BranchPoint reverse = start;
  reverse.tangent = -start.tangent;
  const Walk fwd = walk(sys, start, s);
  const Walk back = walk(sys, reverse, s);
  switches.insert(switches.end(), fwd.switches.begin(), fwd.switches.end());
  switches.insert(switches.end(), back.switches.begin(), back.switches.end());
  return joinWalks(id, back, fwd);
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

std::vector<Branch> continueFrom(const ContinuationSystem& sys, const Vec& x0, double p0,
                                 const ContinuationSettings& s) {
  const Region region = regionAt(sys, x0, p0);
  const auto x = solveAt(sys, x0, p0, region);
  if (!x)
    throw std::runtime_error("Newton does not converge at the start, p = " + numberText(p0, 10));
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

}  // namespace metrosync::continuation
