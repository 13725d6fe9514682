#include "sim/analysis/periodic_orbit/shooting.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "base/number_text.h"

namespace metrosync::orbit {

namespace {

// Newton's step is halved while the residual grows by more than this factor (a start far from
// the orbit, or across an event that appears); after kMaxHalvings the full step is taken anyway.
constexpr double kGrowth = 2.0;
constexpr int kMaxHalvings = 4;
// A column of dP/du this close to a unit vector is that of a neutral coordinate: the
// variational equations give it to ~1e-12 (rounding), a coupled one differs by O(epsilon).
constexpr double kNeutral = 1e-9;

}  // namespace

double Orbit::maxModulus() const {
  int skip = -1;  // the neutral multiplier: the one nearest to 1
  if (neutral)
    for (int i = 0; i < multipliers.size(); ++i)
      if (skip < 0 || std::abs(multipliers(i) - 1.0) < std::abs(multipliers(skip) - 1.0)) skip = i;
  double m = 0.0;
  for (int i = 0; i < multipliers.size(); ++i)
    if (i != skip) m = std::max(m, std::abs(multipliers(i)));
  return m;
}

CVec multipliersOf(const Mat& jacobian) {
  if (jacobian.size() == 0) return CVec();
  Eigen::EigenSolver<Mat> es(jacobian, false);
  CVec m = es.eigenvalues();
  std::sort(m.data(), m.data() + m.size(),
            [](const std::complex<double>& a, const std::complex<double>& b) {
              if (std::abs(a) != std::abs(b)) return std::abs(a) > std::abs(b);
              return a.imag() > b.imag();
            });
  return m;
}

bool neutralVelocity(const Section& section, const Mat& jacobian) {
  for (int k = 0; k < section.dim(); ++k) {
    if (section.component(k) != ScaledModel::kV) continue;
    return (jacobian.col(k) - Vec::Unit(section.dim(), k)).lpNorm<Eigen::Infinity>() < kNeutral;
  }
  return false;
}

std::optional<Orbit> shoot(const ReturnMap& map, const Vec& u0, double period_guess,
                           const NewtonSettings& s, std::string* why, const Mat* basis) {
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return std::nullopt;
  };
  const Mat B = basis ? *basis : Mat::Identity(u0.size(), u0.size());
  auto reduced = [&](const Pass& p) { return Vec(B.transpose() * (p.u1 - p.u0)); };
  double period = period_guess;
  try {
    Pass p = map.pass(B * (B.transpose() * u0), period, true);
    double res = reduced(p).lpNorm<Eigen::Infinity>();
    for (int it = 0; it <= s.max_iterations; ++it) {
      if (res <= s.tolerance) {
        const double whole = (p.u1 - p.u0).lpNorm<Eigen::Infinity>();
        Orbit o{p.u0, p.period, whole, it, p, multipliersOf(p.jacobian)};
        o.neutral = neutralVelocity(map.section(), p.jacobian);
        return o;
      }
      if (it == s.max_iterations) break;
      const Mat J = B.transpose() * p.jacobian * B - Mat::Identity(B.cols(), B.cols());
      const Vec step = B * J.fullPivLu().solve(-reduced(p));
      if (!step.allFinite()) return fail("singular Newton matrix dP/du - I");
      const Vec base = p.u0;
      period = p.period;
      for (int half = 0;; ++half) {
        Pass q = map.pass(base + step * std::ldexp(1.0, -half), period, true);
        const double r = reduced(q).lpNorm<Eigen::Infinity>();
        if (r <= kGrowth * res || half == kMaxHalvings) {
          p = std::move(q);
          res = r;
          break;
        }
      }
    }
    return fail("Newton did not converge in " + std::to_string(s.max_iterations) +
                " iterations (residual " + numberText(res, 3) + ")");
  } catch (const std::exception& e) {  // OrbitFailure, or a piece that cannot be integrated
    return fail(e.what());
  }
}

}  // namespace metrosync::orbit
