#include "tests/continuation/fixtures.h"

#include <algorithm>
#include <cmath>

#include "base/constants.h"
#include "contact/averaged_response.h"
#include "yaml/rig_loader.h"

namespace metrosync::continuation::testing {

namespace {
constexpr double kJ = 2.8, kThetaC = 0.9;

double bisect(double lo, double hi, double s, double nu);
double smallestMu(double s, double nu);
}  // namespace

ScaledParams singleMetronome(double mu) {
  ScaledParams p;
  p.epsilon = 0.073;
  p.friction = FrictionLaw::coulomb(mu);
  p.nu = {0.7};
  p.J = {2.8};
  p.theta_c = {0.9};
  p.alpha = {0.0};
  p.zeta = {0.0};
  p.A_star = {steadyAmplitude(0.7, 2.8, 0.9)};
  p.locked = {false};
  p.theta0 = {0.0};
  p.thetadot0 = {2.0};
  p.tau_end = 300;
  return p;
}

ScaledParams f44(double alpha) {
  const std::string path = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/paper/f4.4-alpha4.yaml";
  char buf[64];
  std::snprintf(buf, sizeof buf, "metronomes.1.alpha=%.17g", alpha);
  return computeScaled(loadRigFile(path, {buf}));
}

Vec singleTicking(const SlowFlowProblem& prob, double mu) {
  const ScaledParams& p = prob.params(mu);
  // dA/dtau = -beta2(A/mu) A - nu A / 2 + (J/pi) sqrt(1 - theta_c^2/A^2) (e3.1a, N = 1): it is
  // < 0 for large A, > 0 just above the upper root; bisect from A = 10 down to A_star
  auto rate = [&](double A) {
    return -coulombBeta2(A / *p.friction.value("mu")) * A - p.nu[0] * A / 2 +
           p.J[0] / kPi * std::sqrt(1 - p.theta_c[0] * p.theta_c[0] / (A * A));
  };
  double lo = *p.A_star[0] * 0.999, hi = 10;
  while (rate(lo) < 0) lo = 0.5 * (lo + p.theta_c[0]);
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (rate(mid) > 0 ? lo : hi) = mid;
  }
  const double A = 0.5 * (lo + hi);
  const double omega = prob.omegaGuess(mu, {std::complex<double>(A)});
  return prob.pack({std::complex<double>(A)}, omega);
}

double worstResidual(const SlowFlowProblem& prob, const std::vector<Branch>& branches) {
  double worst = 0;
  for (const Branch& b : branches)
    for (const BranchPoint& q : b.points) {
      const Vec x = q.y.head(prob.system().n);
      const auto z = prob.unpack(x);
      const auto f = slowFlowRhs(prob.params(q.p()), prob.modes(q.region), z);
      for (size_t i = 0; i < z.size(); ++i)
        worst = std::max(worst, std::abs(f[i] - std::complex<double>(0, prob.omega(x)) * z[i]));
    }
  return worst;
}

double amplitudeRate(double A, double s, double nu) {
  return -coulombBeta2(s) * A - nu * A / 2 + kJ / kPi * std::sqrt(1 - kThetaC * kThetaC / (A * A));
}

namespace {
double bisect(double lo, double hi, double s, double nu) {
  const bool rising = amplitudeRate(lo, s, nu) < 0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((amplitudeRate(mid, s, nu) < 0) == rising ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// min over the roots A of G(., s) of A / s (inf when there is none). The rate is negative at
// theta_c and for large A, positive between the two roots: bracket at its maximum.
double smallestMu(double s, double nu) {
  double best = kThetaC, rate = amplitudeRate(kThetaC, s, nu);
  for (double A = kThetaC; A < 6; A += 5e-3)  // a bracket only
    if (amplitudeRate(A, s, nu) > rate) best = A, rate = amplitudeRate(A, s, nu);
  if (rate <= 0) return INFINITY;
  return std::min(bisect(kThetaC, best, s, nu), bisect(best, 10.0, s, nu)) / s;
}

}  // namespace

double closedFormFoldMu(double nu, double s_lo, double s_hi) {
  double lo = s_lo, hi = s_hi, best = INFINITY, at = s_lo;
  for (double s = s_lo; s < s_hi; s += 0.01)
    if (smallestMu(s, nu) < best) best = smallestMu(s, nu), at = s;
  lo = at - 0.01, hi = at + 0.01;
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  for (int i = 0; i < 200 && hi - lo > 1e-9; ++i) {  // mu is flat there: 1e-18
    const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
    if (smallestMu(a, nu) < smallestMu(b, nu))
      hi = b;
    else
      lo = a;
  }
  return smallestMu(0.5 * (lo + hi), nu);
}

std::vector<std::complex<double>> rk4SlowFlow(const ScaledParams& p, const SlowFlowModes& modes,
                                              std::vector<std::complex<double>> z, double T,
                                              int n) {
  using Z = std::vector<std::complex<double>>;
  const double h = T / n;
  auto f = [&](const Z& w) { return slowFlowRhs(p, modes, w); };
  auto axpy = [](const Z& a, double s, const Z& b) {
    Z r(a.size());
    for (size_t i = 0; i < a.size(); ++i) r[i] = a[i] + s * b[i];
    return r;
  };
  for (int k = 0; k < n; ++k) {
    const Z k1 = f(z), k2 = f(axpy(z, h / 2, k1)), k3 = f(axpy(z, h / 2, k2)),
            k4 = f(axpy(z, h, k3));
    for (size_t i = 0; i < z.size(); ++i)
      z[i] += h / 6 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
  return z;
}

}  // namespace metrosync::continuation::testing
