#include "sim/analysis/periodic_orbit/family_map.h"

#include <cmath>

namespace metrosync::orbit {

namespace {
// dF/d(p / span) by central differences at +-kParamStep in p / span: truncation O(1e-10) of the
// derivative, the return map's noise (~1e-12) divided by 1e-5.
constexpr double kParamStep = 1e-5;
// The corrector gives up after this many Newton iterations (it converges in 2-4 from a
// predictor on a smooth stretch), or when the residual grows past kDiverged times the first.
constexpr int kMaxCorrections = 8;
constexpr double kDiverged = 10.0;
}  // namespace

FamilyMap::FamilyMap(const OrbitProblem& problem, double span) : prob_(problem), span_(span) {}

void FamilyMap::setSymmetry(SymmetryKind kind) {
  if (!map_) throw std::logic_error("FamilyMap::setSymmetry before mapAt");
  red_ = reduction(*map_, kind);
}

void FamilyMap::pinVelocity(double velocity) {
  const Section& sec = mapAt(map_p_).section();
  Mat B = red_.B;
  offset_ = Vec::Zero(sec.dim());
  for (int k = 0; k < sec.dim(); ++k)
    if (sec.component(k) == ScaledModel::kV) B.row(k).setZero(), offset_(k) = velocity;
  // an orthonormal basis of what is left (a column that was the velocity alone drops out)
  Eigen::ColPivHouseholderQR<Mat> qr(B);
  const Mat Q = qr.householderQ();
  red_.B = Q.leftCols(qr.rank());
  pinned_ = true;
}

const ReturnMap& FamilyMap::mapAt(double p) {
  if (!map_ || p != map_p_) {
    map_ = std::make_unique<ReturnMap>(prob_.rig_at(p), prob_.pendulum, prob_.ret);
    map_p_ = p;
    dim_ = map_->section().dim();
    if (red_.B.size() == 0) red_ = reduction(*map_, SymmetryKind::None);
  }
  return *map_;
}

Vec FamilyMap::yOf(const FamilyPoint& q) const {
  const Vec w = wOf(q.orbit.u);
  Vec y(w.size() + 1);
  y << w, q.p / span_;
  return y;
}

std::optional<FamilyPoint> FamilyMap::correct(const Vec& y0, const Vec& c, double value,
                                              const Vec& dFdp, double period_guess,
                                              int* iterations) {
  const int k = static_cast<int>(y0.size()) - 1;
  const Mat& B = red_.B;
  Vec y = y0;
  double period = period_guess, first = -1.0;
  try {
    for (int it = 0; it <= kMaxCorrections; ++it) {
      const double p = y(k) * span_;
      Pass pass = mapAt(p).pass(uOf(y.head(k)), period, true);
      y.head(k) = wOf(pass.u0);
      const Vec F = B.transpose() * (pass.u1 - pass.u0);
      const double res = F.lpNorm<Eigen::Infinity>();
      if (first < 0) first = res;
      if (res <= prob_.newton.tolerance && std::abs(c.dot(y) - value) <= prob_.newton.tolerance) {
        if (iterations) *iterations = it;
        FamilyPoint q;
        q.p = p;
        const double whole = (pass.u1 - pass.u0).lpNorm<Eigen::Infinity>();
        q.orbit = Orbit{pass.u0, pass.period, whole, it, pass, multipliersOf(pass.jacobian)};
        q.orbit.neutral = pinned_ && neutralVelocity(mapAt(p).section(), pass.jacobian);
        return q;
      }
      if (it == kMaxCorrections || res > kDiverged * std::max(first, 1e-8)) break;
      Mat A(k + 1, k + 1);
      A.topLeftCorner(k, k) = B.transpose() * pass.jacobian * B - Mat::Identity(k, k);
      A.topRightCorner(k, 1) = dFdp;
      A.bottomRows(1) = c.transpose();
      Vec rhs(k + 1);
      rhs << -F, value - c.dot(y);
      const Vec step = A.fullPivLu().solve(rhs);
      if (!step.allFinite()) break;
      y += step;
      period = pass.period;
    }
  } catch (const std::exception&) {  // the engine, the orbit, or the rig at p
  }
  return std::nullopt;
}

Vec FamilyMap::dFdp(const Vec& u, double p, double period) {
  const double h = kParamStep * span_;
  auto at = [&](double q) -> std::optional<Vec> {
    try {
      const Pass pass = mapAt(q).pass(u, period, false);
      return Vec(red_.B.transpose() * (pass.u1 - pass.u0));
    } catch (const std::exception&) {
      return std::nullopt;
    }
  };
  const auto plus = at(p + h), minus = at(p - h);
  if (plus && minus) return (*plus - *minus) / (2 * kParamStep);
  const auto mid = at(p);  // at the edge of the rig's range (mu = 0): one-sided
  if (!mid || !(plus || minus)) throw OrbitFailure("dF/dp: the return map fails around p");
  return plus ? Vec((*plus - *mid) / kParamStep) : Vec((*mid - *minus) / kParamStep);
}

void FamilyMap::complete(FamilyPoint& q, const Vec& ref, bool measures) {
  q.dFdp = dFdp(q.orbit.u, q.p, q.orbit.period);
  q.tangent = ref;  // for bordered(): replaced below
  const int k = static_cast<int>(red_.B.cols());
  Vec e = Vec::Zero(k + 1);
  e(k) = 1.0;
  Vec t = bordered(q).fullPivLu().solve(e);
  t.normalize();
  q.tangent = t.dot(ref) < 0 ? Vec(-t) : t;
  if (measures) q.measures = measureOrbit(mapAt(q.p), q.orbit);
}

Mat FamilyMap::bordered(const FamilyPoint& q) const {
  const Mat& B = red_.B;
  const int k = static_cast<int>(B.cols());
  Mat A(k + 1, k + 1);
  A.topLeftCorner(k, k) = B.transpose() * q.orbit.pass.jacobian * B - Mat::Identity(k, k);
  A.topRightCorner(k, 1) = q.dFdp;
  A.bottomRows(1) = q.tangent.transpose();
  return A;
}

Mat FamilyMap::antisymmetric(const FamilyPoint& q) const {
  const Mat& C = red_.C;
  if (C.size() == 0) return Mat();
  return C.transpose() * q.orbit.pass.jacobian * C - Mat::Identity(C.cols(), C.cols());
}

}  // namespace metrosync::orbit
