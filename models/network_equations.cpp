#include "models/network_equations.h"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>

namespace metrosync::network {

NetworkEquations::NetworkEquations(const Network& net) : couplings_(net.couplings) {
  lay_.platforms = static_cast<int>(net.platforms.size());
  for (int p = 0; p < lay_.platforms; ++p) {
    const NetworkPlatform& np = net.platforms[p];
    // the pendulums' constants exactly as the single-platform equations make them
    const direct::MetronomeEquations one(np.rig);
    Block b;
    b.moves = np.rig.platform.friction.platformMoves();
    b.below = np.on;
    b.mass = np.rig.totalMass();
    b.k = np.rig.platform.spring_N_m;
    b.c = np.spring_c_Ns_m;
    // the normal force carries what rests on it
    b.friction = np.rig.platform.friction.platform(net.carriedMass(p) * net.gravity_m_s2);
    b.first = static_cast<int>(pend_.size());
    b.count = one.numSwinging();
    for (int j = 0; j < one.numSwinging(); ++j) {
      direct::PendulumConstants pc = one.pendulum(j);
      pc.rig_index += net.firstMetronome(p);  // the metronome's global number
      pend_.push_back(pc);
    }
    blocks_.push_back(b);
  }
  lay_.n = static_cast<int>(pend_.size());
  c_.resize(lay_.n);
  r_.resize(lay_.n);
  meff_.resize(lay_.platforms);
}

bool NetworkEquations::stuck(int p, const std::vector<PlatformMode>& modes) const {
  return blocks_[p].moves && blocks_[p].friction.setValued() && modes[p] == PlatformMode::Stuck;
}

double NetworkEquations::slipVelocity(const double* y, int p) const {
  const int b = blocks_[p].below;
  return y[lay_.v(p)] - (b >= 0 ? y[lay_.v(b)] : 0.0);
}

void NetworkEquations::schur(const double* y, int p, double& meff, double& g) const {
  const Block& b = blocks_[p];
  meff = b.mass;
  g = -b.k * y[lay_.x(p)] - b.c * y[lay_.v(p)];
  for (int j = b.first; j < b.first + b.count; ++j) {
    const direct::PendulumConstants& q = pend_[j];
    const double th = y[lay_.theta(j)], w = y[lay_.omega(j)];
    const double s = std::sin(th), co = std::cos(th);
    c_[j] = q.mL * co;
    r_[j] = -q.mgL * s - q.damping * w;  // e1.1a without the platform's push
    const double c_over_I = c_[j] * q.inv_inertia;
    g += q.mL * s * w * w - c_over_I * r_[j];  // e1.1c after eliminating thetaddot_j
    meff -= c_over_I * c_[j];
  }
}

void NetworkEquations::accelerations(const double* y, const std::vector<PlatformMode>& modes,
                                     std::vector<double>& a, std::vector<double>* lambda) const {
  const int np = lay_.platforms;
  std::vector<double> f(np, 0.0);
  std::vector<int> held;  // stuck contacts
  for (int p = 0; p < np; ++p) {
    if (!blocks_[p].moves) continue;
    schur(y, p, meff_[p], f[p]);
  }
  for (const Coupling& k : couplings_) {
    const double F =
        -k.k_N_m * (y[lay_.x(k.a)] - y[lay_.x(k.b)]) - k.c_Ns_m * (y[lay_.v(k.a)] - y[lay_.v(k.b)]);
    f[k.a] += F;
    f[k.b] -= F;
  }
  for (int p = 0; p < np; ++p) {
    const Block& b = blocks_[p];
    if (!b.moves) continue;
    if (stuck(p, modes)) {
      held.push_back(p);
      continue;
    }
    const double F = b.friction.force(slipVelocity(y, p), modes[p]);
    f[p] += F;
    if (b.below >= 0) f[b.below] -= F;
  }
  a.assign(np, 0.0);
  for (int p = 0; p < np; ++p)
    if (blocks_[p].moves) a[p] = f[p] / meff_[p];
  if (lambda) lambda->assign(np, 0.0);
  if (held.empty()) return;
  // J M^-1 J^T lambda = -(J a_free): each stuck contact's relative acceleration made zero
  const int s = static_cast<int>(held.size());
  auto effect = [&](int q, int p) {  // d a_q / d lambda_p
    if (q < 0 || !blocks_[q].moves) return 0.0;
    const double sign = (q == p) - (q == blocks_[p].below);
    return sign / meff_[q];
  };
  Eigen::MatrixXd A(s, s);
  Eigen::VectorXd rhs(s);
  for (int i = 0; i < s; ++i) {
    const int p = held[i], b = blocks_[p].below;
    rhs(i) = -(a[p] - (b >= 0 ? a[b] : 0.0));
    for (int k = 0; k < s; ++k) A(i, k) = effect(p, held[k]) - effect(b, held[k]);
  }
  const Eigen::VectorXd lam = A.ldlt().solve(rhs);
  for (int k = 0; k < s; ++k) {
    const int p = held[k], b = blocks_[p].below;
    a[p] += lam(k) / meff_[p];
    if (b >= 0 && blocks_[b].moves) a[b] -= lam(k) / meff_[b];
    if (lambda) (*lambda)[p] = lam(k);
  }
}

void NetworkEquations::rhs(const double* y, const std::vector<PlatformMode>& modes,
                           double* dy) const {
  std::vector<double> a;
  accelerations(y, modes, a, nullptr);
  double damping = 0.0, friction = 0.0, dampers = 0.0;
  for (int p = 0; p < lay_.platforms; ++p) {
    const Block& b = blocks_[p];
    dy[lay_.x(p)] = b.moves ? y[lay_.v(p)] : 0.0;
    dy[lay_.v(p)] = a[p];
    for (int j = b.first; j < b.first + b.count; ++j) {
      const direct::PendulumConstants& q = pend_[j];
      const double w = y[lay_.omega(j)];
      const double r = -q.mgL * std::sin(y[lay_.theta(j)]) - q.damping * w;
      const double c = b.moves ? q.mL * std::cos(y[lay_.theta(j)]) : 0.0;
      dy[lay_.theta(j)] = w;
      dy[lay_.omega(j)] = (r - c * a[p]) * q.inv_inertia;  // e1.1a, b
      damping += q.damping * w * w;
    }
    if (!b.moves) continue;
    const double v = y[lay_.v(p)];
    dampers += b.c * v * v;
    if (!stuck(p, modes)) friction += b.friction.power(slipVelocity(y, p), modes[p]);
  }
  for (const Coupling& k : couplings_) {
    const double u = y[lay_.v(k.a)] - y[lay_.v(k.b)];
    dampers += k.c_Ns_m * u * u;
  }
  dy[lay_.dampingWork()] = damping;
  dy[lay_.frictionWork()] = friction;
  dy[lay_.damperWork()] = dampers;
}

std::vector<double> NetworkEquations::holdingForces(const double* y,
                                                    const std::vector<PlatformMode>& modes) const {
  std::vector<double> a, lambda;
  accelerations(y, modes, a, &lambda);
  return lambda;
}

double NetworkEquations::inverseMass(const double* y, int p) const {
  if (p < 0 || !blocks_[p].moves) return 0.0;
  double meff = 0.0, g = 0.0;
  schur(y, p, meff, g);
  return 1.0 / meff;
}

double NetworkEquations::applyImpulse(double* y, const std::vector<double>& pin,
                                      const std::vector<double>& contact) const {
  double dT = 0.0;  // sum of impulse . (u + du / 2)
  for (int p = 0; p < lay_.platforms; ++p) {
    const Block& b = blocks_[p];
    double dv = 0.0;
    if (b.moves) {
      double P = contact.empty() ? 0.0 : contact[p];
      for (int q = 0; q < lay_.platforms; ++q)
        if (blocks_[q].below == p && !contact.empty()) P -= contact[q];
      // the arrow [[M, c^T], [c, diag(I)]] [dv; dw] = [P; pin], platform first (Schur)
      double meff = 0.0, g = 0.0, rhs = P;
      schur(y, p, meff, g);
      for (int j = b.first; j < b.first + b.count; ++j)
        rhs -= c_[j] * pend_[j].inv_inertia * pin[j];
      dv = rhs / meff;
      dT += P * (y[lay_.v(p)] + 0.5 * dv);
      y[lay_.v(p)] += dv;
    }
    for (int j = b.first; j < b.first + b.count; ++j) {
      const double c = b.moves ? c_[j] : 0.0;
      const double dw = (pin[j] - c * dv) * pend_[j].inv_inertia;
      dT += pin[j] * (y[lay_.omega(j)] + 0.5 * dw);
      y[lay_.omega(j)] += dw;
    }
  }
  return dT;
}

double NetworkEquations::contactMobility(const double* y, int p) const {
  return inverseMass(y, p) + inverseMass(y, blocks_[p].below);
}

double NetworkEquations::momentum(const double* y) const {
  double P = 0.0;
  for (int p = 0; p < lay_.platforms; ++p) {
    const Block& b = blocks_[p];
    if (!b.moves) continue;
    P += b.mass * y[lay_.v(p)];
    for (int j = b.first; j < b.first + b.count; ++j)
      P += pend_[j].mL * std::cos(y[lay_.theta(j)]) * y[lay_.omega(j)];
  }
  return P;
}

double NetworkEquations::energy(const double* y) const {
  double e = 0.0;
  for (int p = 0; p < lay_.platforms; ++p) {
    const Block& b = blocks_[p];
    const double v = b.moves ? y[lay_.v(p)] : 0.0, x = y[lay_.x(p)];
    e += 0.5 * b.mass * v * v + 0.5 * b.k * x * x;
    for (int j = b.first; j < b.first + b.count; ++j) {
      const direct::PendulumConstants& q = pend_[j];
      const double co = std::cos(y[lay_.theta(j)]), w = y[lay_.omega(j)];
      e += q.mL * co * v * w + 0.5 * q.inertia * w * w - q.mgL * co;
    }
  }
  for (const Coupling& k : couplings_) {
    const double d = y[lay_.x(k.a)] - y[lay_.x(k.b)];
    e += 0.5 * k.k_N_m * d * d;
  }
  return e;
}

}  // namespace metrosync::network
