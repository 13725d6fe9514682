#include "sim/analysis/continuation/merge.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "base/constants.h"

namespace metrosync::continuation {

namespace {

// A start state this close (the parameter in units of the range, amplitudes, phases) to a
// branch is on it: far above a Newton solution's error, below the gap between distinct states.
constexpr double kSameState = 1e-3;
// A point of a branch this close to another branch's polyline is on it: above the chord error of
// the longest steps (0.05 of arclength: ~3e-3), below the distance of distinct branches.
constexpr double kOnPolyline = 1e-2;
// The fraction of a branch's (or curve's) points on an earlier one that makes it a duplicate
// (two distinct branches share only the points where they cross).
constexpr double kDuplicateFraction = 0.8;
// Special points of one type at parameters this close (relative) are the same point: they are
// located to ~1e-11.
constexpr double kSameParameter = 1e-7;
// ... with sorted amplitudes this close: the same state up to the metronomes' order.
constexpr double kSameAmplitudes = 1e-6;
// A curve point this close (in units of the keys' spans) to another curve is on it.
constexpr double kSameCurve = 1e-3;

// The point's coordinates: (p / span, A, psi), psi unwrapped about `about`'s.
std::vector<double> coords(double p, const std::vector<double>& A, const std::vector<double>& psi,
                           double span, const std::vector<double>* about) {
  std::vector<double> u = {p / span};
  u.insert(u.end(), A.begin(), A.end());
  for (size_t j = 0; j < psi.size(); ++j)
    u.push_back(about ? (*about)[j] + std::remainder(psi[j] - (*about)[j], kTwoPi) : psi[j]);
  return u;
}

// Distance from q to the segment [a, b].
double segmentDistance(const std::vector<double>& q, const std::vector<double>& a,
                       const std::vector<double>& b) {
  double ab2 = 0, t = 0;
  for (size_t i = 0; i < q.size(); ++i)
    ab2 += (b[i] - a[i]) * (b[i] - a[i]), t += (q[i] - a[i]) * (b[i] - a[i]);
  t = ab2 > 0 ? std::clamp(t / ab2, 0.0, 1.0) : 0.0;
  double d = 0;
  for (size_t i = 0; i < q.size(); ++i) d += std::pow(q[i] - a[i] - t * (b[i] - a[i]), 2);
  return std::sqrt(d);
}

// A segment whose parameter alone is farther than `within` by this much (relative to the
// numbers' size) is skipped: its computed distance cannot come out below `within` by rounding.
constexpr double kSkipMargin = 1e-9;

// Each branch's points (by id), in order.
using BranchPoints = std::vector<std::vector<const ResultPoint*>>;
BranchPoints pointsByBranch(const ContinuationResult& r) {
  BranchPoints by(r.branches.size());
  for (const ResultPoint& q : r.points) by.at(q.branch).push_back(&q);
  return by;
}

// Whether the state lies within `within` of a branch's polyline (its points, in order): the
// distance to one of its segments below it. Segments whose parameter alone puts them farther are
// not measured.
bool onBranch(const std::vector<const ResultPoint*>& points, double p, const std::vector<double>& A,
              const std::vector<double>& psi, double span, double within) {
  const double x0 = p / span;
  const ResultPoint* prev = nullptr;
  for (const ResultPoint* at : points) {
    const ResultPoint& q = *at;
    const ResultPoint& from = prev ? *prev : q;
    prev = &q;
    const double lo = std::min(from.value, q.value) / span,
                 hi = std::max(from.value, q.value) / span;
    const double gap = x0 < lo ? lo - x0 : x0 > hi ? x0 - hi : 0.0;
    if (gap - within > kSkipMargin * (within + std::abs(x0) + std::abs(lo) + std::abs(hi)))
      continue;
    const std::vector<double> x = coords(p, A, psi, span, &q.psi);
    const std::vector<double> b = coords(q.value, q.A, q.psi, span, &q.psi);
    const std::vector<double> a = coords(from.value, from.A, from.psi, span, &q.psi);
    if (segmentDistance(x, a, b) < within) return true;
  }
  return false;
}

bool inFamily(const ResultFamily& f, double p, const std::vector<double>& A,
              const std::vector<double>& psi) {
  for (const ResultFamilyPoint& q : f.points) {
    if (std::abs(q.value - p) > kSameParameter * std::max(1.0, std::abs(p))) continue;
    bool in = true;
    for (size_t i = 0; i < A.size(); ++i)
      in = in && A[i] > q.A_min[i] - kSameState && A[i] < q.A_max[i] + kSameState;
    for (size_t j = 0; j < psi.size() && !q.closed; ++j) {
      const double mid = 0.5 * (q.psi_min[j] + q.psi_max[j]);
      const double d = mid + std::remainder(psi[j] - mid, kTwoPi);
      in = in && d > q.psi_min[j] - kSameState && d < q.psi_max[j] + kSameState;
    }
    if (in) return true;
  }
  return false;
}

// Whether family branch b is a family already kept (its first point a member of one).
bool knownFamily(const ContinuationResult& r, const ResultBranch& b, const std::vector<int>& kept) {
  const auto q = std::find_if(r.points.begin(), r.points.end(),
                              [&](const ResultPoint& p) { return p.branch == b.id; });
  for (const ResultFamily& f : r.families)
    if (f.branch != b.id && std::count(kept.begin(), kept.end(), f.branch) && q != r.points.end() &&
        inFamily(f, q->value, q->A, q->psi))
      return true;
  return false;
}

// The branches kept (ids in order) after dropping duplicates: a family duplicates a family, a
// branch a branch (a family's representative may lie beside a branch leaving its edge).
std::vector<int> keptBranches(const ContinuationResult& r) {
  const double span = std::max(std::abs(r.to - r.from), 1e-300);
  const BranchPoints by_branch = pointsByBranch(r);
  std::vector<int> kept;
  for (const ResultBranch& b : r.branches) {
    if (b.neutral > 0) {
      if (!knownFamily(r, b, kept)) kept.push_back(b.id);
      continue;
    }
    long on = 0, all = 0;
    for (const ResultPoint* at : by_branch[b.id]) {
      const ResultPoint& q = *at;
      ++all;
      for (int k : kept)
        if (r.branches[k].neutral == 0 &&
            onBranch(by_branch[k], q.value, q.A, q.psi, span, kOnPolyline)) {
          ++on;
          break;
        }
    }
    if (all == 0 || on < kDuplicateFraction * all) kept.push_back(b.id);
  }
  return kept;
}

bool sameSpecial(const ResultSpecial& a, const ResultSpecial& b, bool* mirrored) {
  if (a.type != b.type ||
      std::abs(a.at.value - b.at.value) > kSameParameter * std::max(1.0, std::abs(a.at.value)))
    return false;
  std::vector<double> x = a.at.A, y = b.at.A;
  double direct = 0;
  for (size_t i = 0; i < x.size(); ++i) direct = std::max(direct, std::abs(x[i] - y[i]));
  std::sort(x.begin(), x.end());
  std::sort(y.begin(), y.end());
  for (size_t i = 0; i < x.size(); ++i)
    if (std::abs(x[i] - y[i]) > kSameAmplitudes) return false;
  *mirrored = direct > kSameAmplitudes;
  return true;
}

void mergeSpecials(ContinuationResult& r) {
  std::vector<ResultSpecial> out;
  std::vector<int> copies;
  for (const ResultSpecial& s : r.special) {
    bool mirrored = false, found = false;
    for (size_t i = 0; i < out.size() && !found; ++i)
      if (sameSpecial(out[i], s, &mirrored)) {
        found = true;
        if (mirrored) ++copies[i];
      }
    if (!found) out.push_back(s), copies.push_back(0);
  }
  for (size_t i = 0; i < out.size(); ++i)
    if (copies[i] > 0)
      out[i].detail += "; the same point on " + std::to_string(copies[i]) +
                       " copy(ies) of the state with identical metronomes exchanged";
  r.special = std::move(out);
}

// Distance from (p1, p2) to a curve's polyline in units of the spans.
double toCurve(const FoldCurve& c, double p1, double p2, double span1, double span2) {
  double best = std::numeric_limits<double>::infinity();
  const std::vector<double> q = {p1 / span1, p2 / span2};
  for (size_t k = 0; k < c.points.size(); ++k) {
    const FoldCurvePoint& b = c.points[k];
    const FoldCurvePoint& a = k ? c.points[k - 1] : b;
    best = std::min(best,
                    segmentDistance(q, {a.p1 / span1, a.p2 / span2}, {b.p1 / span1, b.p2 / span2}));
  }
  return best;
}

}  // namespace

bool alreadyFollowed(const ContinuationResult& r, double p, const std::vector<double>& A,
                     const std::vector<double>& psi, double span) {
  const BranchPoints by_branch = pointsByBranch(r);
  for (const ResultBranch& b : r.branches)
    if (onBranch(by_branch[b.id], p, A, psi, span, kSameState)) return true;
  for (const ResultFamily& f : r.families)
    if (inFamily(f, p, A, psi)) return true;
  return false;
}

void mergeDuplicates(ContinuationResult& r) {
  const std::vector<int> kept = keptBranches(r);
  std::map<int, int> id;
  for (size_t k = 0; k < kept.size(); ++k) id[kept[k]] = static_cast<int>(k);
  auto dropped = [&](int b) { return id.count(b) == 0; };
  std::vector<ResultBranch> branches;
  for (ResultBranch b : r.branches)
    if (!dropped(b.id)) b.id = id[b.id], branches.push_back(b);
  r.branches = std::move(branches);
  r.points.erase(std::remove_if(r.points.begin(), r.points.end(),
                                [&](const ResultPoint& q) { return dropped(q.branch); }),
                 r.points.end());
  for (ResultPoint& q : r.points) q.branch = id[q.branch];
  r.special.erase(std::remove_if(r.special.begin(), r.special.end(),
                                 [&](const ResultSpecial& s) { return dropped(s.at.branch); }),
                  r.special.end());
  for (ResultSpecial& s : r.special) s.at.branch = id[s.at.branch];
  r.families.erase(std::remove_if(r.families.begin(), r.families.end(),
                                  [&](const ResultFamily& f) { return dropped(f.branch); }),
                   r.families.end());
  for (size_t k = 0; k < r.families.size(); ++k)
    r.families[k].id = static_cast<int>(k), r.families[k].branch = id[r.families[k].branch];
  mergeSpecials(r);
}

bool onACurve(const std::vector<FoldCurve>& curves, CurveKind kind, double p1, double p2,
              double span1, double span2) {
  for (const FoldCurve& c : curves)
    if (c.kind == kind && toCurve(c, p1, p2, span1, span2) < kSameCurve) return true;
  return false;
}

void mergeCurves(std::vector<FoldCurve>& curves, double span1, double span2) {
  std::vector<FoldCurve> kept;
  for (const FoldCurve& c : curves) {
    long on = 0;
    for (const FoldCurvePoint& q : c.points)
      if (onACurve(kept, c.kind, q.p1, q.p2, span1, span2)) ++on;
    if (c.points.empty() || on < kDuplicateFraction * static_cast<double>(c.points.size()))
      kept.push_back(c);
  }
  curves = std::move(kept);
}

}  // namespace metrosync::continuation
