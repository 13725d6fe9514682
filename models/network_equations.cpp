#include "models/network_equations.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "models/platform_arrow_rates.h"

namespace metrosync::network {

NetworkEquations::NetworkEquations(const Network& net) : couplings_(net.couplings) {
  lay_.platforms = static_cast<int>(net.platforms.size());
  for (int p = 0; p < lay_.platforms; ++p) {
    const NetworkPlatform& np = net.platforms[p];
    Block b;
    b.moves = np.rig.platform.friction.platformMoves();
    b.below = np.on;
    b.mass = np.rig.totalMass();
    b.k = np.rig.platform.spring_N_m;
    b.c = np.spring_c_Ns_m;
    // the normal force carries what rests on it
    b.friction = np.rig.platform.friction.platform(net.carriedMass(p) * net.gravity_m_s2);
    arrows_.emplace_back(np.rig, b.friction);
    const PlatformArrow& one = arrows_.back();
    b.first = static_cast<int>(pend_.size());
    b.count = one.numSwinging();
    for (int j = 0; j < one.numSwinging(); ++j) {
      PendulumConstants pc = one.pendulum(j);
      pc.rig_index += net.firstMetronome(p);  // the metronome's global number
      pend_.push_back(pc);
    }
    lay_.dampers = lay_.dampers || (b.moves && b.c != 0);
    blocks_.push_back(b);
  }
  for (const Coupling& k : couplings_) lay_.dampers = lay_.dampers || k.c_Ns_m != 0;
  lay_.n = static_cast<int>(pend_.size());
  meff_.resize(lay_.platforms);
  single_arrow_ =
      lay_.platforms == 1 && blocks_[0].below < 0 && couplings_.empty() && !lay_.dampers;
}

NetworkEquations::NetworkEquations(const Rig& rig) : NetworkEquations(networkOfOne(rig)) {}

// The single board's right-hand side: its arrow's fused pass inlined whole, one call per
// evaluation from the stepper (as the single rig's always was).
template <int N>
void NetworkEquations::rhsN(const double* y, PlatformMode mode, double* dy) const {
  const int n = N > 0 ? N : lay_.n;
  const ArrowPower power =
      arrows_[0].tableRates<N>(y, y + 2, y + 2 + n, mode, dy, dy + 2, dy + 2 + n);
  dy[2 + 2 * n] = power.damping;   // lay_.dampingWork()
  dy[3 + 2 * n] = power.friction;  // lay_.frictionWork()
}

#define METROSYNC_SINGLE_BOARD_RHS(N) \
  template void NetworkEquations::rhsN<N>(const double*, PlatformMode, double*) const;
METROSYNC_SINGLE_BOARD_RHS(NetworkEquations::kAnyN)
METROSYNC_SINGLE_BOARD_RHS(1)
METROSYNC_SINGLE_BOARD_RHS(2)
METROSYNC_SINGLE_BOARD_RHS(3)
METROSYNC_SINGLE_BOARD_RHS(4)
METROSYNC_SINGLE_BOARD_RHS(5)
METROSYNC_SINGLE_BOARD_RHS(6)
METROSYNC_SINGLE_BOARD_RHS(7)
METROSYNC_SINGLE_BOARD_RHS(8)
#undef METROSYNC_SINGLE_BOARD_RHS

bool NetworkEquations::stuck(int p, const std::vector<PlatformMode>& modes) const {
  return blocks_[p].moves && blocks_[p].friction.setValued() && modes[p] == PlatformMode::Stuck;
}

double NetworkEquations::slipVelocity(const double* y, int p) const {
  const int b = blocks_[p].below;
  return y[lay_.v(p)] - (b >= 0 ? y[lay_.v(b)] : 0.0);
}

void NetworkEquations::schur(const double* y, int p, double& meff, double& g) const {
  const Block& b = blocks_[p];
  arrows_[p].schurPass(y + lay_.theta(b.first), y + lay_.omega(b.first), y[lay_.x(p)], meff, g);
  g -= b.c * y[lay_.v(p)];  // the ground damper
}

void NetworkEquations::accelerations(const double* y, const std::vector<PlatformMode>& modes,
                                     std::vector<double>& a, std::vector<double>* lambda) const {
  const int np = lay_.platforms;
  std::vector<double> f(np, 0.0);
  std::vector<int> held;  // stuck contacts
  // every platform's arrow (a fixed one's too: its pendulums' c_j and r_j for rhs())
  for (int p = 0; p < np; ++p) schur(y, p, meff_[p], f[p]);
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
  accelerations(y, modes, a, nullptr);  // leaves each arrow's c_j and r_j at y
  double damping = 0.0, friction = 0.0, dampers = 0.0;
  for (int p = 0; p < lay_.platforms; ++p) {
    const Block& b = blocks_[p];
    dy[lay_.x(p)] = b.moves ? y[lay_.v(p)] : 0.0;
    dy[lay_.v(p)] = a[p];
    const double* w = y + lay_.omega(b.first);
    std::copy(w, w + b.count, dy + lay_.theta(b.first));
    arrows_[p].pendulumAccelerations(a[p], dy + lay_.omega(b.first));  // e1.1a, b
    damping += arrows_[p].dampingPower(w);
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
  if (lay_.dampers) dy[lay_.damperWork()] = dampers;
}

std::vector<double> NetworkEquations::holdingForces(const double* y,
                                                    const std::vector<PlatformMode>& modes) const {
  std::vector<double> a, lambda;
  accelerations(y, modes, a, &lambda);
  return lambda;
}

double NetworkEquations::inverseMass(const double* y, int p) const {
  if (p < 0 || !blocks_[p].moves) return 0.0;
  return arrows_[p].mobility(y + lay_.theta(blocks_[p].first));
}

double NetworkEquations::applyImpulse(double* y, const std::vector<double>& pin,
                                      const std::vector<double>& contact) const {
  double dT = 0.0;  // sum of impulse . (u + du / 2)
  for (int p = 0; p < lay_.platforms; ++p) {
    const Block& b = blocks_[p];
    // the impulse on platform p's x: its own contact's, less those of the platforms on it
    double P = contact.empty() ? 0.0 : contact[p];
    for (int q = 0; q < lay_.platforms; ++q)
      if (blocks_[q].below == p && !contact.empty()) P -= contact[q];
    dT += arrows_[p].applyImpulse(y + lay_.theta(b.first), y + lay_.v(p), y + lay_.omega(b.first),
                                  pin.data() + b.first, P);
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
    e += arrows_[p].energy(y[lay_.x(p)], y[lay_.v(p)], y + lay_.theta(b.first),
                           y + lay_.omega(b.first));
  }
  for (const Coupling& k : couplings_) {
    const double d = y[lay_.x(k.a)] - y[lay_.x(k.b)];
    e += 0.5 * k.k_N_m * d * d;
  }
  return e;
}

}  // namespace metrosync::network
