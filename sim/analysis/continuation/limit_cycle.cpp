#include "sim/analysis/continuation/limit_cycle.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>

#include "base/constants.h"
#include "base/number_text.h"
#include "sim/analysis/continuation/arclength.h"
#include "sim/analysis/continuation/derivatives.h"
#include "sim/analysis/continuation/newton.h"
#include "sim/analysis/continuation/parameter_scale.h"

namespace metrosync::continuation {

namespace {

// The first cycle's amplitude along the Hopf eigenvector, relative to max(1, |y_h|): small
// enough to be near the Hopf point (p moves by ~l1 a^2), then smaller ones when Newton fails.
constexpr double kStartAmplitude = 1e-2;
constexpr int kStartTries = 4;  // down to kStartAmplitude / 64
// The first cycle's period lies within this fraction of the Hopf period 2 pi / w (it moves by
// O(a^2)); anything else is another solution of the shooting equations.
constexpr double kStartPeriodTolerance = 0.2;
// The shooting residual comes from difference Jacobians one level down (~1e-10 noise); 1e-9 is
// what the corrector reaches reliably (as for the fold curves, fold_curve.cpp).
constexpr double kCycleTolerance = 1e-9;
// Multipliers this close to the unit circle count as on it (the trivial one's accuracy).
constexpr double kUnitCircle = 1e-6;
// The continuation's borders (exits): the period's limit, the orbit's margin.
constexpr int kPeriodBorder = 0, kMarginBorder = 1;
// The branch ends where the orbit comes this close to a border of its region (in the border
// functions' units: amplitude or |Z|): nearer, the escapement's amplitude term sqrt(A - theta_c)
// has derivatives ten times its size and more, and the shooting's Newton crawls.
constexpr double kMarginStop = 1e-2;
// The arclength of the shooting's unknowns counts each of the kSegments arc starts: steps this
// many times longer move the orbit by what a step moves a locked state.
const double kArcWeight = std::sqrt(static_cast<double>(kSegments));

// The Hopf eigenvector q (f_y q = i w q, w > 0), rotated so that Re q and Im q are orthogonal.
struct HopfMode {
  double omega = 0.0;
  Vec re, im;
};

HopfMode hopfMode(const CycleField& f, const Vec& y_h, double p_h) {
  const Mat A = jacobianOf([&](const Vec& y) { return f.rhs(y, p_h); }, y_h);
  Eigen::EigenSolver<Mat> es(A);
  Eigen::Index k = -1;
  for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i) {
    const auto l = es.eigenvalues()(i);
    if (l.imag() > 0 && (k < 0 || std::abs(l.real()) < std::abs(es.eigenvalues()(k).real()))) k = i;
  }
  if (k < 0) throw std::runtime_error("the Hopf point has no complex pair of eigenvalues");
  Eigen::VectorXcd q = es.eigenvectors().col(k);
  // q e^{i t} has Re . Im = 0 where tan 2t = 2 Re.Im / (|Im|^2 - |Re|^2)
  const double a = q.real().dot(q.imag()), b = q.imag().squaredNorm() - q.real().squaredNorm();
  q *= std::polar(1.0, 0.5 * std::atan2(2 * a, b));
  q /= q.norm();
  return {es.eigenvalues()(k).imag(), q.real(), q.imag()};
}

// The first cycle at amplitude a along Re q: y_j = y_h + a u_j with the unknowns (u, T, p) and
// the equations (phi(y_j, T / M; p) - y_{j+1}) / a = 0, u_0 . Im q = 0 (phase), u_0 . Re q = 1
// (amplitude). In units of a the equations stay well-conditioned as a -> 0, where in y itself
// the period is undetermined (d phi / dT = f = O(a)) and Newton may run off to another solution.
// Returns (y_0, .., y_{M-1}, T, p).
std::optional<Vec> firstCycle(const MultipleShooting& ms, const Vec& y_h, double p_h,
                              const HopfMode& q, double a) {
  const int n = static_cast<int>(y_h.size()), N = ms.size() - 1;
  auto toY = [&](const Vec& v) {
    Vec u(N + 1);
    for (int j = 0; j < kSegments; ++j) u.segment(j * n, n) = y_h + a * v.segment(j * n, n);
    u(N) = v(N);
    return u;
  };
  ContinuationSystem start;
  start.n = N + 2;
  start.residual = [&](const Vec& v, double, const Region&) {
    Vec out(N + 2);
    out << ms.residual(toY(v), v(N + 1)) / a, v.head(n).dot(q.im), v.head(n).dot(q.re) - 1.0;
    return out;
  };
  start.jacobian = [&](const Vec& v, double, const Region&) {
    const double p = v(N + 1), h = centralStep(p);
    Mat J = Mat::Zero(N + 2, N + 2);
    J.topLeftCorner(N, N + 1) = ms.jacobian(toY(v), p);
    J.block(0, N, N, 1) /= a;  // d/dT; d/du_j = a d/dy_j / a
    J.block(0, N + 1, N, 1) =
        (ms.residual(toY(v), p + h) - ms.residual(toY(v), p - h)) / (2 * h * a);
    J.block(N, 0, 1, n) = q.im.transpose();
    J.block(N + 1, 0, 1, n) = q.re.transpose();
    return J;
  };
  start.tolerance = kCycleTolerance;
  const double T_h = 2 * kPi / q.omega;
  const double scale = 1.0 / q.re.squaredNorm();
  Vec v0(N + 2);
  v0.head(N + 1) = ms.sample(
      [&](double t) {
        return Vec(scale * (q.re * std::cos(q.omega * t) - q.im * std::sin(q.omega * t)));
      },
      T_h);
  v0(N + 1) = p_h;
  const auto v = solveAt(start, v0, 0.0, Region{});
  // another solution of the shooting equations (the orbit run backwards, or several times over)
  // is not the cycle born at the Hopf point, whose period starts at T_h
  if (!v || std::abs((*v)(N)-T_h) > kStartPeriodTolerance * T_h) return std::nullopt;
  Vec out(N + 2);
  out << toY(*v), (*v)(N + 1);
  return out;
}

// The continuation system in u = (y_0, .., y_{M-1}, T): the arcs join, y_0 on the phase plane;
// borders (exits) where the period passes kMaxPeriodFactor T_h and where the orbit touches the
// region's border.
// y_0 relative to the orbit's centre (the mean of the arcs' starts).
Vec fromCentre(const Vec& u, int n) {
  Vec c = Vec::Zero(n);
  for (int j = 0; j < kSegments; ++j) c += u.segment(j * n, n);
  return u.head(n) - c / kSegments;
}

// A step through zero amplitude: the cycle shrank onto a Hopf point and the step came out on the
// same cycles again (y_0 now on the other side of the centre: the phase condition's other
// crossing). The branch ends there.
std::string throughHopf(const Vec& y, const Vec& y_next, int n) {
  if (fromCentre(y, n).dot(fromCentre(y_next, n)) >= 0) return "";
  return "the cycle shrinks onto a Hopf point (the next step passed through zero amplitude)";
}

// The phase condition (y_0 - y_r) . d = 0: the hyperplane through the last cycle's y_0 across
// the orbit there (d along the chord y_1 - y_{M-1}), moved with every accepted cycle. A fixed
// hyperplane (through the Hopf point) stops cutting the cycles once they shrink around another
// equilibrium, and the branch would turn back there on the same cycles.
struct PhasePlane {
  Vec y, d;
  void through(const Vec& u, int n) {
    y = u.head(n);
    d = (u.segment(n, n) - u.segment((kSegments - 1) * n, n)).normalized();
  }
};

ContinuationSystem shootingSystem(const MultipleShooting& ms, int n, const Vec& u0, double T_h) {
  const int N = ms.size() - 1;
  auto plane = std::make_shared<PhasePlane>();
  plane->through(u0, n);
  ContinuationSystem sys;
  sys.n = N + 1;
  sys.residual = [&ms, plane, n, N](const Vec& u, double p, const Region&) {
    Vec r(N + 1);
    r << ms.residual(u, p), (u.head(n) - plane->y).dot(plane->d);
    return r;
  };
  sys.jacobian = [&ms, plane, n, N](const Vec& u, double p, const Region&) {
    Mat J = Mat::Zero(N + 1, N + 1);
    J.topRows(N) = ms.jacobian(u, p);
    J.block(N, 0, 1, n) = plane->d.transpose();
    return J;
  };
  sys.accepted = [plane, n](const Vec& y) { plane->through(y, n); };
  sys.borders = [&ms, T_h, N](const Vec& u, double p) {
    Vec b(2);
    b << kMaxPeriodFactor * T_h - u(N), std::min(ms.margin(u, p), 1.0) - kMarginStop;
    return b;
  };
  sys.stop = [n](const Vec& y, const Vec& y_next) { return throughHopf(y, y_next, n); };
  sys.exits = [](int) { return true; };
  sys.eigenvalues = [](const Vec&, double, const Region&) { return CVec(); };
  sys.tolerance = kCycleTolerance;
  sys.branch_points = false;  // branch points of cycles are not reported
  return sys;
}

CyclePoint describe(const MultipleShooting& ms, int n, const Vec& u, double p) {
  CyclePoint c;
  c.p = p, c.period = u(u.size() - 1), c.y0 = u.head(n);
  c.y_min = c.y_max = c.y0;
  c.orbit = ms.orbit(u, p);
  for (const Vec& y : c.orbit) c.y_min = c.y_min.cwiseMin(y), c.y_max = c.y_max.cwiseMax(y);
  Mat M;
  ms.jacobian(u, p, &M);
  c.multipliers = M.eigenvalues();
  Eigen::Index k = 0;
  (c.multipliers.array() - 1.0).abs().minCoeff(&k);
  c.trivial_error = std::abs(c.multipliers(k) - 1.0);
  c.stable = true;
  for (Eigen::Index i = 0; i < c.multipliers.size(); ++i)
    if (i != k && std::abs(c.multipliers(i)) >= 1 - kUnitCircle) c.stable = false;
  return c;
}

// The kind of the multiplier that left the unit circle between a and b.
std::string stabilityChange(const CyclePoint& a, const CyclePoint& b) {
  const CyclePoint& unstable = a.stable ? b : a;
  std::complex<double> worst = 0;
  for (const auto& m : unstable.multipliers)
    if (std::abs(m - 1.0) > unstable.trivial_error && std::abs(m) > std::abs(worst)) worst = m;
  const std::string kind = std::abs(worst.imag()) > kUnitCircle
                               ? "a complex pair crosses the unit circle (Neimark-Sacker: a torus)"
                           : worst.real() < 0 ? "a multiplier crosses -1 (period doubling)"
                                              : "a multiplier crosses +1";
  return "between p = " + numberText(a.p, 8) + " and " + numberText(b.p, 8) + ": " + kind;
}

// A multiplier crossing +1 between two points beside a located fold is that fold (in folds):
// not another change.
void dropFoldChanges(CycleBranch& c) {
  std::vector<std::string> kept;
  size_t k = 0;
  for (size_t i = 1; i < c.points.size(); ++i) {
    if (c.points[i - 1].stable == c.points[i].stable) continue;
    const double lo = std::min(c.points[i - 1].p, c.points[i].p);
    const double hi = std::max(c.points[i - 1].p, c.points[i].p), w = 2 * (hi - lo) + 1e-12;
    const bool fold = std::any_of(c.folds.begin(), c.folds.end(), [&](const CyclePoint& f) {
      return f.p > lo - w && f.p < hi + w;
    });
    const std::string& text = c.changes[k++];
    if (!(fold && text.find("crosses +1") != std::string::npos)) kept.push_back(text);
  }
  c.changes = std::move(kept);
}

// The walk's end in words.
std::string endOf(const Walk& w, double p_end, double T_h) {
  if (w.exit == kPeriodBorder)
    return "the period passes " + numberText(kMaxPeriodFactor, 8) + " times the Hopf period (" +
           numberText(kMaxPeriodFactor * T_h, 8) +
           ": a homoclinic orbit?) at p = " + numberText(p_end, 8);
  if (w.exit == kMarginBorder)
    return "the orbit comes within " + numberText(kMarginStop, 8) +
           " of a border of the vector field at p = " + numberText(p_end, 8);
  return w.end + (std::isnan(w.end_p) ? "" : " at p = " + numberText(p_end, 8));
}

}  // namespace

CycleBranch continueCycleFromHopf(const CycleField& f, const Vec& y_h, double p_h,
                                  const ContinuationSettings& s) {
  const HopfMode q = hopfMode(f, y_h, p_h);
  const MultipleShooting ms(f);
  double a = kStartAmplitude * std::max(1.0, y_h.norm());
  std::optional<Vec> v;
  for (int tries = 0; !v && tries < kStartTries; ++tries, a *= 0.25)
    v = firstCycle(ms, y_h, p_h, q, a);
  if (!v) throw std::runtime_error("the first cycle near the Hopf point does not converge");
  const int N = ms.size();  // unknowns: arcs and T
  const double T_h = 2 * kPi / q.omega, p0 = (*v)(N);
  const ParameterScale scale(p0, s);
  const ContinuationSystem sys = scale.system(shootingSystem(ms, f.n, v->head(N), T_h));
  Vec y(N + 1), ref = Vec::Zero(N + 1);
  y << v->head(N), 0.0;
  ref.head(f.n) = q.re;  // outwards: the amplitude along Re q grows
  const Region r = regionAt(sys, y.head(N), 0.0);
  const BranchPoint start = makePoint(sys, y, tangentAt(sys, y, ref, r), r);
  ContinuationSettings inner = scale.settings(s);
  inner.step *= kArcWeight, inner.step_max *= kArcWeight;
  const Walk w = walkFrom(sys, start, inner, s.max_points);
  CycleBranch out;
  out.hopf_p = p_h, out.hopf_frequency = q.omega, out.max_points = w.max_points;
  for (BranchPoint bp : w.points) {
    scale.restore(bp);
    CyclePoint c = describe(ms, f.n, bp.y.head(N), bp.p());
    if (!out.points.empty() && out.points.back().stable != c.stable)
      out.changes.push_back(stabilityChange(out.points.back(), c));
    out.points.push_back(std::move(c));
  }
  for (Bifurcation e : w.special) {
    if (e.type != BifurcationType::Fold) continue;
    scale.restore(e.point);
    out.folds.push_back(describe(ms, f.n, e.point.y.head(N), e.point.p()));
  }
  dropFoldChanges(out);
  out.end = endOf(w, out.points.back().p, T_h);
  out.into_hopf = w.end.rfind("the cycle shrinks onto a Hopf point", 0) == 0;
  return out;
}

}  // namespace metrosync::continuation
