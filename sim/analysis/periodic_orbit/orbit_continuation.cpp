#include "sim/analysis/periodic_orbit/orbit_continuation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "base/number_text.h"
#include "sim/analysis/periodic_orbit/family_map.h"
#include "sim/analysis/periodic_orbit/special_points.h"

namespace metrosync::orbit {

namespace {

// Step control: grow after an easy corrector, give up below kMinStepFraction of the first step.
constexpr double kStepGrow = 1.5;
constexpr int kEasyIterations = 3;
constexpr double kMinStepFraction = 1e-6;
// Special points are located to this arclength (y = (u, p / span)): 1e-9 of the range in p.
constexpr double kLocateTolerance = 1e-9;
constexpr int kLocateIterations = 60;
// Two special points of one type closer than this share of the range in p are one (located to
// 1e-9 of it: the same zero found again from the next step).
constexpr double kSamePoint = 1e-6;

struct Walk {
  std::vector<FamilyPoint> points;
  std::vector<OrbitBifurcation> special;
  std::string end;
};

class Walker {
 public:
  Walker(FamilyMap& fm, const FamilySettings& s) : fm_(fm), s_(s) {}
  Walk walk(const FamilyPoint& start);

 private:
  std::optional<FamilyPoint> along(const FamilyPoint& a, double sigma, bool measures,
                                   int* iterations = nullptr);
  std::optional<FamilyPoint> toBound(const FamilyPoint& a, const FamilyPoint& b);
  std::optional<FamilyPoint> locateZero(const FamilyPoint& a, double h, double ga, double gb,
                                        const std::function<double(const FamilyPoint&)>& g);
  std::optional<FamilyPoint> locateEvents(const FamilyPoint& a, double h, const EventCounts& eb);
  // tests: the test functions too (not only the events)
  void specials(const FamilyPoint& a, const FamilyPoint& b, double h, Walk& w, bool tests = true);
  void add(Walk& w, OrbitBifurcation b) const;
  void grazingEnd(const FamilyPoint& a, double h, Walk& w);
  bool outside(double p) const { return p > s_.p_max || p < s_.p_min; }

  FamilyMap& fm_;
  const FamilySettings& s_;
};

std::optional<FamilyPoint> Walker::along(const FamilyPoint& a, double sigma, bool measures,
                                         int* iterations) {
  const Vec y0 = fm_.yOf(a);
  auto q = fm_.correct(y0 + sigma * a.tangent, a.tangent, a.tangent.dot(y0) + sigma, a.dFdp,
                       a.orbit.period, iterations);
  if (!q) return std::nullopt;
  try {
    fm_.complete(*q, a.tangent, measures);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  return q;
}

// The orbit at the end of the range, between a (inside) and b (outside).
std::optional<FamilyPoint> Walker::toBound(const FamilyPoint& a, const FamilyPoint& b) {
  const double bound = b.p > s_.p_max ? s_.p_max : s_.p_min;
  if (a.p == bound) return std::nullopt;  // the start, on the bound, leaving the range
  const Vec ya = fm_.yOf(a), yb = fm_.yOf(b);
  const double w = (bound - a.p) / (b.p - a.p);
  Vec c = Vec::Zero(ya.size());
  c(ya.size() - 1) = 1.0;
  auto q = fm_.correct(ya + w * (yb - ya), c, bound / fm_.span(), a.dFdp, a.orbit.period);
  if (!q) return std::nullopt;
  try {
    fm_.complete(*q, a.tangent, true);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  return q;
}

// Illinois regula falsi on the arclength sigma in [0, h] for g(point(sigma)) = 0.
std::optional<FamilyPoint> Walker::locateZero(const FamilyPoint& a, double h, double ga, double gb,
                                              const std::function<double(const FamilyPoint&)>& g) {
  double lo = 0.0, hi = h, flo = ga, fhi = gb;
  int side = 0;
  std::optional<FamilyPoint> best;
  for (int it = 0; it < kLocateIterations && hi - lo > kLocateTolerance; ++it) {
    double x = flo != fhi ? lo - flo * (hi - lo) / (fhi - flo) : 0.5 * (lo + hi);
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    auto q = along(a, x, false);
    if (!q) {  // the corrector failed inside the step: shrink the bracket blindly
      (it % 2 ? hi : lo) = x;
      continue;
    }
    const double fx = g(*q);
    best = q;
    if ((fx > 0) == (fhi > 0)) {
      hi = x, fhi = fx;
      if (side == 1) flo *= 0.5;
      side = 1;
    } else {
      lo = x, flo = fx;
      if (side == -1) fhi *= 0.5;
      side = -1;
    }
  }
  if (!best) return std::nullopt;
  if (auto final = along(a, 0.5 * (lo + hi), true)) return final;
  try {  // the last zero's estimate that converged, with its averages
    best->measures = measureOrbit(fm_.mapAt(best->p), best->orbit);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  return best;
}

// Bisection for the first sigma whose orbit has b's events.
std::optional<FamilyPoint> Walker::locateEvents(const FamilyPoint& a, double h,
                                                const EventCounts& eb) {
  double lo = 0.0, hi = h;
  std::optional<FamilyPoint> best;
  while (hi - lo > kLocateTolerance) {
    const double x = 0.5 * (lo + hi);
    auto q = along(a, x, true);
    if (q && q->measures.events == eb) {
      hi = x;
      best = q;
    } else {
      lo = x;
    }
  }
  return best;
}

void Walker::add(Walk& w, OrbitBifurcation b) const {
  for (const OrbitBifurcation& o : w.special)
    if (o.type == b.type && std::abs(o.point.p - b.point.p) < kSamePoint * fm_.span()) return;
  w.special.push_back(std::move(b));
}

void Walker::specials(const FamilyPoint& a, const FamilyPoint& b, double h, Walk& w, bool tests) {
  for (TestKind kind : tests ? testKinds() : std::vector<TestKind>{}) {
    auto g = [&](const FamilyPoint& q) { return testFunction(kind, fm_, q); };
    const double ga = g(a), gb = g(b);
    if (!(ga * gb < 0)) continue;
    auto q = s_.locate ? locateZero(a, h, ga, gb, g) : std::optional<FamilyPoint>(b);
    if (!q) q = b;
    if (auto bif = classify(kind, *q, a, b, fm_.mapAt(q->p).model(), fm_.symmetry().kind))
      add(w, *bif);
  }
  if (a.measures.events != b.measures.events) {
    auto q = s_.locate ? locateEvents(a, h, b.measures.events) : std::optional<FamilyPoint>(b);
    add(w, classifyEvents(q ? *q : b, a, b));
  }
}

// Where the corrector fails just past a: a pass from the last predictor; when a metronome's ticks
// per period differ there, the family ended at a grazing point (the tick's energy appears or
// vanishes at once, the return map jumps): reported at a.
void Walker::grazingEnd(const FamilyPoint& a, double h, Walk& w) {
  const Vec y = fm_.yOf(a) + h * a.tangent;
  const int k = static_cast<int>(y.size()) - 1;
  try {
    const ReturnMap& map = fm_.mapAt(y(k) * fm_.span());
    const Pass pass = map.pass(fm_.uAt(y.head(k)), a.orbit.period, false);
    FamilyPoint b = a;
    b.p = y(k) * fm_.span();
    b.measures.events = countEvents(map, pass);
    if (b.measures.events.ticks == a.measures.events.ticks) return;
    OrbitBifurcation g = classifyEvents(a, a, b);
    g.detail +=
        " (the family ends here: the tick's impulse appears or vanishes at once, so "
        "the return map jumps)";
    add(w, g);
  } catch (const std::exception&) {
  }
}

Walk Walker::walk(const FamilyPoint& start) {
  Walk w;
  w.points.push_back(start);
  FamilyPoint cur = start;
  const double span = fm_.span();
  const double h0 = std::min((s_.step > 0 ? s_.step : span / 50) / span, s_.step_max);
  double h = h0;
  double first_failure = 0.0;  // the step at which the current run of corrector failures began
  while (static_cast<int>(w.points.size()) < s_.max_points) {
    int iterations = 0;
    auto next = along(cur, h, true, &iterations);
    if (!next) {
      if (!(first_failure > 0)) first_failure = h;
      h *= 0.5;
      if (h >= kMinStepFraction * h0) continue;
      w.end = "the corrector fails after p = " + numberText(cur.p, 10) +
              " (the orbit ends or the engine fails)";
      grazingEnd(cur, first_failure, w);
      return w;
    }
    first_failure = 0.0;
    if (outside(next->p)) {
      if (auto last = toBound(cur, *next)) {
        // a bound where the velocity turns neutral (mu = 0): its tangent is not defined there
        const bool neutral = !fm_.pinned() && neutralVelocity(fm_.mapAt(last->p).section(),
                                                              last->orbit.pass.jacobian);
        specials(cur, *last, cur.tangent.dot(fm_.yOf(*last) - fm_.yOf(cur)), w, !neutral);
        w.points.push_back(*last);
      }
      w.end = "reached the end of the range, p = " + numberText(w.points.back().p, 10);
      if (w.points.size() == 1) w.end = "the start lies on the end of the range";
      return w;
    }
    const size_t before = w.special.size();
    const bool neutral =
        !fm_.pinned() && neutralVelocity(fm_.mapAt(next->p).section(), next->orbit.pass.jacobian);
    specials(cur, *next, h, w, !neutral);
    if (neutral) {
      w.end = "the orbits stop being isolated after p = " + numberText(cur.p, 10) +
              ": the platform's velocity becomes neutral (a multiplier is exactly 1: its slip "
              "reverses only at ticks, or nothing brakes it)";
      return w;
    }
    w.points.push_back(*next);
    for (size_t k = before; k < w.special.size(); ++k)
      if (w.special[k].meets_symmetric) {
        w.end = "a symmetry-breaking branch point at p = " + numberText(w.special[k].point.p, 10) +
                ": beyond it the family is the mirror image of this one";
        return w;
      }
    cur = *next;
    if (iterations <= kEasyIterations) h = std::min(h * kStepGrow, s_.step_max);
  }
  w.end = "max points reached at p = " + numberText(cur.p, 10);
  return w;
}

}  // namespace

namespace {

// A start this close to a symmetric orbit (scaled section state) is followed as one: a settled
// run reaches a stable symmetric orbit to ~1e-10 (its contraction over the run), while an
// asymmetric orbit near a branch point is ~1e-2 away a step from it.
constexpr double kSymmetricStart = 1e-7;

// Whether the key keeps the pair identical (a key of one metronome breaks the exchange): the
// rig a little away from p0 on either side.
bool keepsSymmetry(const OrbitProblem& problem, double p0, double span) {
  for (double side : {1.0, -1.0}) {
    try {
      return identicalPair(ScaledModel(problem.rig_at(p0 + side * 1e-3 * span)));
    } catch (const std::exception&) {  // outside the rig's range that way
    }
  }
  return false;
}

SymmetryKind symmetryOfStart(const ReturnMap& map, const Orbit& start) {
  const ScaledModel& m = map.model();
  if (inPhaseDistance(m, start.pass.z0) < kSymmetricStart) return SymmetryKind::InPhase;
  if (antiPhaseDistance(m, start.pass.z0) < kSymmetricStart) return SymmetryKind::AntiPhase;
  return SymmetryKind::None;
}

}  // namespace

namespace {

// The family through q0 (completed), both ways.
Family bothWays(FamilyMap& fm, const FamilyPoint& q0, const FamilySettings& settings) {
  Walker walker(fm, settings);
  const Walk fwd = walker.walk(q0);
  FamilyPoint r0 = q0;
  r0.tangent = -q0.tangent;
  const Walk back = walker.walk(r0);
  Family f;
  f.symmetry = fm.symmetry().kind;
  for (auto it = back.points.rbegin(); it != back.points.rend(); ++it) {
    f.points.push_back(*it);
    f.points.back().tangent = -it->tangent;
  }
  f.points.insert(f.points.end(), fwd.points.begin() + 1, fwd.points.end());
  f.special = back.special;
  f.special.insert(f.special.end(), fwd.special.begin(), fwd.special.end());
  f.end_backward = back.end;
  f.end_forward = fwd.end;
  return f;
}

// The first step off a symmetric branch point along its antisymmetric kernel direction (scaled
// section state): far outside the engine's tick-merging slack (~1e-9), small against the
// orbits' size (~1); then 4 and 16 times smaller if the corrector falls back or fails.
constexpr double kSwitchStep = 0.02;
// A switched orbit closer than this to the symmetric ones fell back onto them.
constexpr double kOffSymmetric = 1e-6;

}  // namespace

Family continueFamily(const OrbitProblem& problem, const Orbit& start, double p0,
                      const FamilySettings& settings) {
  FamilyMap fm(problem, settings.p_max - settings.p_min);
  const ReturnMap& map0 = fm.mapAt(p0);
  Orbit first = start;
  const SymmetryKind sym = keepsSymmetry(problem, p0, settings.p_max - settings.p_min)
                               ? symmetryOfStart(map0, start)
                               : SymmetryKind::None;
  if (sym != SymmetryKind::None) {
    const SymmetryReduction red = reduction(map0, sym);
    if (auto s = shoot(map0, start.u, start.period, problem.newton, nullptr, &red.B)) {
      first = *s;
      fm.setSymmetry(sym);
    }
  }
  if (neutralVelocity(map0.section(), first.pass.jacobian))
    fm.pinVelocity(first.pass.z0(ScaledModel::kV));
  FamilyPoint q0;
  q0.p = p0;
  q0.orbit = first;
  q0.orbit.neutral = fm.pinned();
  const int k = static_cast<int>(fm.symmetry().B.cols());
  Vec ref = Vec::Zero(k + 1);
  ref(k) = 1.0;  // first along increasing p
  fm.complete(q0, ref, true);
  return bothWays(fm, q0, settings);
}

std::optional<Family> switchBranch(const OrbitProblem& problem, SymmetryKind symmetry,
                                   const FamilyPoint& at, const FamilySettings& settings) {
  const double span = settings.p_max - settings.p_min;
  FamilyMap sym(problem, span);
  sym.mapAt(at.p);
  sym.setSymmetry(symmetry);
  const Mat A = sym.antisymmetric(at);
  if (A.size() == 0) return std::nullopt;
  Eigen::JacobiSVD<Mat> svd(A, Eigen::ComputeFullV);
  const Vec d = sym.symmetry().C * svd.matrixV().col(A.cols() - 1);
  FamilyMap fm(problem, span);
  fm.mapAt(at.p);
  const int m = static_cast<int>(d.size());
  Vec t = Vec::Zero(m + 1);
  t.head(m) = d.normalized();
  FamilyPoint bp = at;
  const Vec y0 = fm.yOf(bp);
  try {
    const Vec dFdp = fm.parameterDerivative(bp);
    for (double h : {kSwitchStep, kSwitchStep / 4, kSwitchStep / 16}) {
      auto q = fm.correct(y0 + h * t, t, t.dot(y0) + h, dFdp, at.orbit.period);
      // (the map at q's p: mapAt replaces the one before)
      if (!q || symmetryDistance(*q, fm.mapAt(q->p).model()) < kOffSymmetric) continue;
      fm.complete(*q, t, true);
      return bothWays(fm, *q, settings);
    }
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

}  // namespace metrosync::orbit
