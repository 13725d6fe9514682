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
#include "sim/ode/rk_stepper.h"

namespace metrosync::continuation {

namespace {

// Verner 7(6) with 200 fixed steps per period: local errors ~(T/200)^8, below 1e-11 for the slow
// flow's periods (~5-30 in tau), so the flow map is accurate to far better than the shooting
// tolerance while staying a smooth function of (y0, T, p).
constexpr int kStepsPerPeriod = kCycleSteps;
// The first cycle's amplitude along the Hopf eigenvector, relative to max(1, |y_h|): small
// enough to be near the Hopf point (p moves by ~l1 a^2), large enough that the shooting system
// is far from its degenerate limit (every T solves it at a = 0).
constexpr double kStartAmplitude = 1e-2;
constexpr int kStartTries = 4;  // down to kStartAmplitude / 64
// The shooting residual comes from a difference Jacobian one level down (~1e-10 noise); 1e-9 is
// what the corrector reaches reliably (as for the fold curves, fold_curve.cpp).
constexpr double kCycleTolerance = 1e-9;
// The branch stops where the period passes this multiple of the Hopf period: the fixed step
// count no longer resolves the orbit (a period growing without bound: a homoclinic orbit).
constexpr double kMaxPeriodFactor = 5.0;
// Multipliers this close to the unit circle count as on it (the trivial one's accuracy).
constexpr double kUnitCircle = 1e-6;

struct FieldRhs : ode::OdeRhs {
  const CycleField& f;
  double p;
  Vec y, dy;
  FieldRhs(const CycleField& field, double param) : f(field), p(param), y(field.n), dy(field.n) {}
  void eval(const double* in, double* out) override {
    for (int i = 0; i < f.n; ++i) y(i) = in[i];
    dy = f.rhs(y, p);
    for (int i = 0; i < f.n; ++i) out[i] = dy(i);
  }
};

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

// The shooting system in (y0, T) with parameter p.
ContinuationSystem shootingSystem(const CycleField& f, const Vec& y_h, const Vec& d) {
  ContinuationSystem sys;
  sys.n = f.n + 1;
  sys.residual = [&f, y_h, d](const Vec& u, double p, const Region&) {
    const Vec y0 = u.head(f.n);
    Vec r(f.n + 1);
    r.head(f.n) = flowMap(f, y0, u(f.n), p, kStepsPerPeriod) - y0;
    r(f.n) = (y0 - y_h).dot(d);
    return r;
  };
  sys.eigenvalues = [](const Vec&, double, const Region&) { return CVec(); };
  sys.tolerance = kCycleTolerance;
  return sys;
}

// The first cycle: amplitude a along Re q held, p free (Newton on (y0, T, p) via solveAt with the
// amplitude as its parameter).
std::optional<Vec> firstCycle(const CycleField& f, const ContinuationSystem& shoot, const Vec& y_h,
                              double p_h, const HopfMode& q, double a) {
  ContinuationSystem start;
  start.n = f.n + 2;
  start.residual = [&](const Vec& v, double amp, const Region& r) {
    Vec out(f.n + 2);
    out.head(f.n + 1) = shoot.residual(v.head(f.n + 1), v(f.n + 1), r);
    out(f.n + 1) = (v.head(f.n) - y_h).dot(q.re) - amp;
    return out;
  };
  start.tolerance = kCycleTolerance;
  Vec v0(f.n + 2);
  v0 << y_h + a * q.re, 2 * kPi / q.omega, p_h;
  return solveAt(start, v0, a, Region{});
}

CyclePoint describe(const CycleField& f, const Vec& u, double p) {
  CyclePoint c;
  c.p = p, c.period = u(f.n), c.y0 = u.head(f.n);
  std::vector<Vec> orbit;
  flowMap(f, c.y0, c.period, p, kStepsPerPeriod, &orbit);
  c.y_min = c.y_max = c.y0;
  for (const Vec& y : orbit) c.y_min = c.y_min.cwiseMin(y), c.y_max = c.y_max.cwiseMax(y);
  const Mat M =
      jacobianOf([&](const Vec& y) { return flowMap(f, y, c.period, p, kStepsPerPeriod); }, c.y0);
  c.multipliers = M.eigenvalues();
  Eigen::Index k = 0;
  (c.multipliers.array() - 1.0).abs().minCoeff(&k);
  c.trivial_error = std::abs(c.multipliers(k) - 1.0);
  c.stable = true;
  for (Eigen::Index i = 0; i < c.multipliers.size(); ++i)
    if (i != k && std::abs(c.multipliers(i)) >= 1 - kUnitCircle) c.stable = false;
  return c;
}

bool orbitInside(const CycleField& f, const CyclePoint& c) {
  if (!f.inside) return true;
  std::vector<Vec> orbit;
  flowMap(f, c.y0, c.period, c.p, kStepsPerPeriod, &orbit);
  for (const Vec& y : orbit)
    if (!f.inside(y, c.p)) return false;
  return true;
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
                                              : "a multiplier crosses +1 (fold of cycles)";
  return "between p = " + numberText(a.p, 8) + " and " + numberText(b.p, 8) + ": " + kind;
}

}  // namespace

Vec flowMap(const CycleField& f, const Vec& y0, double T, double p, int steps,
            std::vector<Vec>* orbit) {
  FieldRhs rhs(f, p);
  ode::RkStepper stepper(ode::rkTableau("verner76"), f.n, rhs);
  stepper.setTolerances(1.0, std::vector<double>(f.n, 1.0));  // fixed steps: no control
  stepper.restart(0.0, y0.data());
  const double h = T / steps;
  for (int k = 0; k < steps; ++k) {
    stepper.attempt(h);
    stepper.advance();
    if (orbit) orbit->push_back(Eigen::Map<const Vec>(stepper.y(), f.n));
  }
  return Eigen::Map<const Vec>(stepper.y(), f.n);
}

CycleBranch continueCycleFromHopf(const CycleField& f, const Vec& y_h, double p_h,
                                  const ContinuationSettings& s) {
  const HopfMode q = hopfMode(f, y_h, p_h);
  const ContinuationSystem shoot = shootingSystem(f, y_h, q.im);
  // the first amplitude, then smaller ones: a strongly nonlinear Hopf point (large l1) moves p by
  // l1 a^2, out of Newton's reach at the first try
  double a = kStartAmplitude * std::max(1.0, y_h.norm());
  std::optional<Vec> v;
  for (int tries = 0; !v && tries < kStartTries; ++tries, a *= 0.25)
    v = firstCycle(f, shoot, y_h, p_h, q, a);
  if (!v) throw std::runtime_error("the first cycle near the Hopf point does not converge");
  ContinuationSettings inner = s;
  inner.max_branches = 1;
  const Branch b = continueFrom(shoot, v->head(f.n + 1), (*v)(f.n + 1), inner).at(0);
  CycleBranch out;
  out.hopf_p = p_h, out.hopf_frequency = q.omega;
  // from the start outwards: the points whose amplitude along Re q grows away from the Hopf point
  size_t start = 0;
  for (size_t k = 1; k < b.points.size(); ++k)
    if ((b.points[k].y - *v).norm() < (b.points[start].y - *v).norm()) start = k;
  const auto amp = [&](const BranchPoint& bp) { return (bp.y.head(f.n) - y_h).dot(q.re); };
  const double a_start = amp(b.points[start]);
  const bool outward_forward = start + 1 < b.points.size() && amp(b.points[start + 1]) > a_start;
  out.end = outward_forward ? b.end_forward : b.end_backward;
  const double T_h = 2 * kPi / q.omega;
  for (size_t k = start; k < b.points.size(); outward_forward ? ++k : --k) {
    const BranchPoint& bp = b.points[k];
    if (bp.y(f.n) > kMaxPeriodFactor * T_h) {
      out.end = "the period passes " + numberText(kMaxPeriodFactor, 8) +
                " times the Hopf period (a homoclinic orbit?)";
      break;
    }
    CyclePoint c = describe(f, bp.y.head(f.n + 1), bp.p());
    if (!orbitInside(f, c)) {
      out.end = "the orbit reaches a border of the vector field at p = " + numberText(c.p, 8);
      break;
    }
    if (!out.points.empty() && out.points.back().stable != c.stable)
      out.changes.push_back(stabilityChange(out.points.back(), c));
    out.points.push_back(std::move(c));
    if (k == 0) break;
  }
  return out;
}

}  // namespace metrosync::continuation
