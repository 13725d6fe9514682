#include "tests/continuation/fixtures.h"

#include <cmath>

#include "yaml/rig_loader.h"

namespace metrosync::continuation::testing {

ScaledParams singleMetronome(double mu) {
  ScaledParams p;
  p.epsilon = 0.073;
  p.law = FrictionLaw::Coulomb;
  p.mu = mu;
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
    return -coulombBeta2(A / p.mu) * A - p.nu[0] * A / 2 +
           p.J[0] / M_PI * std::sqrt(1 - p.theta_c[0] * p.theta_c[0] / (A * A));
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

}  // namespace metrosync::continuation::testing
