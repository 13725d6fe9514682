#include "sim/analysis/periodic_orbit/shooting.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace metrosync::orbit {

namespace {

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// Newton's step is halved while the residual grows by more than this factor (a start far from
// the orbit, or across an event that appears); after kMaxHalvings the full step is taken anyway.
constexpr double kGrowth = 2.0;
constexpr int kMaxHalvings = 4;

}  // namespace

double Orbit::maxModulus() const {
  return multipliers.size() ? std::abs(multipliers(0)) : 0.0;
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

std::optional<Orbit> shoot(const ReturnMap& map, const Vec& u0, double period_guess,
                           const NewtonSettings& s, std::string* why) {
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return std::nullopt;
  };
  Vec u = u0;
  double period = period_guess;
  try {
    Pass p = map.pass(u, period, true);
    double res = (p.u1 - p.u0).lpNorm<Eigen::Infinity>();
    for (int it = 0; it <= s.max_iterations; ++it) {
      if (res <= s.tolerance) {
        Orbit o{p.u0, p.period, res, it, p, multipliersOf(p.jacobian)};
        return o;
      }
      if (it == s.max_iterations) break;
      const Mat J = p.jacobian - Mat::Identity(p.u0.size(), p.u0.size());
      const Vec step = J.fullPivLu().solve(-(p.u1 - p.u0));
      if (!step.allFinite()) return fail("singular Newton matrix dP/du - I");
      Vec base = p.u0;
      period = p.period;
      for (int half = 0;; ++half) {
        Pass q = map.pass(base + step * std::ldexp(1.0, -half), period, true);
        const double r = (q.u1 - q.u0).lpNorm<Eigen::Infinity>();
        if (r <= kGrowth * res || half == kMaxHalvings) {
          p = std::move(q);
          res = r;
          break;
        }
      }
    }
    return fail("Newton did not converge in " + std::to_string(s.max_iterations) +
                " iterations (residual " + fmt(res) + ")");
  } catch (const OrbitFailure& e) {
    return fail(e.what());
  }
}

}  // namespace metrosync::orbit
