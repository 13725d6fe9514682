#include "models/minimal_equations.h"

#include <cmath>
#include <stdexcept>

#include "models/vector_trig.h"

namespace metrosync {

PlatformFriction platformFriction(const Rig& rig) {
  return rig.platform.friction.platform(rig.totalMass() * rig.gravity_m_s2);
}

}  // namespace metrosync

namespace metrosync::direct {

MetronomeEquations::MetronomeEquations(const Rig& rig)
    : has_platform_(rig.platform.friction.platformMoves()),
      friction_(platformFriction(rig)),
      mass_(rig.totalMass()) {
  const double g = rig.gravity_m_s2;
  for (int i = 0; i < static_cast<int>(rig.metronomes.size()); ++i) {
    const MetronomeSpec& m = rig.metronomes[i];
    if (m.locked) continue;  // rides with the platform: already in M
    PendulumConstants p;
    p.rig_index = i;
    p.mL = m.pendulum_mass_kg * m.length_m;
    p.mgL = p.mL * g;
    p.inertia = m.inertia_kgm2;
    p.inv_inertia = 1.0 / m.inertia_kgm2;
    p.damping = m.damping_kg_s * m.length_m * m.length_m;  // torque -nu-bar L^2 thetadot (e1.1a)
    p.theta_c = m.theta_c_rad;
    p.impulse = m.impulse_Nms;
    pend_.push_back(p);
  }
  layout_.n = static_cast<int>(pend_.size());
  if (has_platform_) {
    if (!(mass_ > 0)) throw std::invalid_argument("the platform's total mass must be > 0");
    spring_ = rig.platform.spring_N_m;
  }
  for (const PendulumConstants& p : pend_) {
    mL_.push_back(p.mL);
    mgL_.push_back(p.mgL);
    inv_inertia_.push_back(p.inv_inertia);
    damping_.push_back(p.damping);
  }
  for (auto* v : {&sin_, &cos_, &c_, &r_, &g_term_, &s_term_}) v->resize(layout_.n);
}

void MetronomeEquations::angleTrig(const double* th) const {
  sinCos(th, sin_.data(), cos_.data(), layout_.n);
}

namespace {

// Pass 1 of the right-hand side: c_j, r_j and the platform's sums on scratch arrays of n values
// each, the terms in vectorizable loops, then the sums in order:
//   G = -k x + sum_j (m_j L_j sin theta_j thetadot_j^2 - c_j r_j / I_j),
//   schur = sum_j c_j^2 / I_j.
// Plain pointers: inlined into rhsBody() they keep its __restrict promises (and its code).
struct SchurSums {
  double G, schur;
};

inline __attribute__((always_inline)) SchurSums schurSums(
    int n, const double* mL, const double* mgL, const double* inv_I, const double* damp,
    double spring, const double* w, const double* x, const double* sn, const double* cs, double* c,
    double* r, double* g_term, double* s_term) {
  for (int j = 0; j < n; ++j) {
    c[j] = mL[j] * cs[j];
    r[j] = -mgL[j] * sn[j] - damp[j] * w[j];
    const double c_over_I = c[j] * inv_I[j];
    g_term[j] = mL[j] * sn[j] * w[j] * w[j] - c_over_I * r[j];
    s_term[j] = c_over_I * c[j];
  }
  double G = -spring * *x, schur = 0.0;  // x read here, as rhs() always has
  for (int j = 0; j < n; ++j) {
    G += g_term[j];
    schur += s_term[j];
  }
  return {G, schur};
}

}  // namespace

// The right-hand side on scratch arrays of n values each (sn, cs: the angles' sin and cos; c, r,
// g_term, s_term: see below): the stack's for a known N, the members' otherwise.
template <int N>
inline __attribute__((always_inline)) void MetronomeEquations::rhsBody(
    const double* y, PlatformMode mode, double* dy, double* __restrict sn, double* __restrict cs,
    double* __restrict c, double* __restrict r, double* __restrict g_term,
    double* __restrict s_term) const {
  const int n = N > 0 ? N : layout_.n;
  const double* __restrict w = y + 2 + n;
  double* __restrict dth = dy + 2;
  double* __restrict dw = dy + 2 + n;
  const double* __restrict mL = mL_.data();
  const double* __restrict mgL = mgL_.data();
  const double* __restrict inv_I = inv_inertia_.data();
  const double* __restrict damp = damping_.data();
  const double v = y[StateLayout::kV];
  sinCos(y + 2, sn, cs, n);
  double damping_power = 0.0;
  for (int j = 0; j < n; ++j) damping_power += damp[j] * w[j] * w[j];

  double a = 0.0;  // xddot
  double friction_power = 0.0;
  const bool platform_moves =
      has_platform_ && !(friction_.setValued() && mode == PlatformMode::Stuck);
  if (platform_moves) {
    // pass 1: c_j, r_j and the platform's Schur-reduced equation Meff xddot = G + F
    const auto [G, schur] = schurSums(n, mL, mgL, inv_I, damp, spring_, w, y + StateLayout::kX, sn,
                                      cs, c, r, g_term, s_term);
    const double F = friction_.force(v, mode);  // the law's force (contact/platform_friction.h)
    friction_power = -F * v;                    // PlatformFriction::power
    a = (G + F) / (mass_ - schur);
    // pass 2: the pendulums
    for (int j = 0; j < n; ++j) dw[j] = (r[j] - c[j] * a) * inv_I[j];
  } else {
    // platform still (fixed, or stuck): each pendulum on its own
    for (int j = 0; j < n; ++j) dw[j] = (-mgL[j] * sn[j] - damp[j] * w[j]) * inv_I[j];
  }
  for (int j = 0; j < n; ++j) dth[j] = w[j];
  dy[StateLayout::kX] = platform_moves ? v : 0.0;
  dy[StateLayout::kV] = a;
  dy[2 + 2 * n] = damping_power;   // layout_.dampingWork()
  dy[3 + 2 * n] = friction_power;  // layout_.frictionWork()
}

template <int N>
void MetronomeEquations::rhsN(const double* y, PlatformMode mode, double* dy) const {
  if constexpr (N > 0) {
    double sn[N], cs[N], c[N], r[N], g_term[N], s_term[N];
    rhsBody<N>(y, mode, dy, sn, cs, c, r, g_term, s_term);
  } else {
    rhsBody<N>(y, mode, dy, sin_.data(), cos_.data(), c_.data(), r_.data(), g_term_.data(),
               s_term_.data());
  }
}

template void MetronomeEquations::rhsN<MetronomeEquations::kAnyN>(const double*, PlatformMode,
                                                                  double*) const;
template void MetronomeEquations::rhsN<1>(const double*, PlatformMode, double*) const;
template void MetronomeEquations::rhsN<2>(const double*, PlatformMode, double*) const;
template void MetronomeEquations::rhsN<3>(const double*, PlatformMode, double*) const;
template void MetronomeEquations::rhsN<4>(const double*, PlatformMode, double*) const;
template void MetronomeEquations::rhsN<5>(const double*, PlatformMode, double*) const;
template void MetronomeEquations::rhsN<6>(const double*, PlatformMode, double*) const;
template void MetronomeEquations::rhsN<7>(const double*, PlatformMode, double*) const;
template void MetronomeEquations::rhsN<8>(const double*, PlatformMode, double*) const;

double MetronomeEquations::holdingForce(const double* y) const {
  const int n = layout_.n;
  const double* w = y + 2 + n;
  angleTrig(y + 2);
  double G = -spring_ * y[StateLayout::kX];
  for (int j = 0; j < n; ++j) {
    const PendulumConstants& p = pend_[j];
    const double s = sin_[j], co = cos_[j];
    const double r = -p.mgL * s - p.damping * w[j];
    G += p.mL * s * w[j] * w[j] - p.mL * co / p.inertia * r;
  }
  return -G;
}

double MetronomeEquations::holdingForceRate(const double* y) const {
  // d/dt of G = sum_j [mL s w^2 - mL co r / I] - k x with xdot = xddot = 0,
  // w' = r / I, r' = -mgL co w - b w'
  const int n = layout_.n;
  const double* w = y + 2 + n;
  angleTrig(y + 2);
  double dG = 0.0;
  for (int j = 0; j < n; ++j) {
    const PendulumConstants& p = pend_[j];
    const double s = sin_[j], co = cos_[j];
    const double r = -p.mgL * s - p.damping * w[j];
    const double dw = r / p.inertia;
    const double dr = -p.mgL * co * w[j] - p.damping * dw;
    dG += p.mL * (co * w[j] * w[j] * w[j] + 2 * s * w[j] * dw) -
          p.mL / p.inertia * (-s * w[j] * r + co * dr);
  }
  return -dG;
}

double MetronomeEquations::applyImpulseAt(const double* th, double* v, double* w,
                                          const double* pin_impulse,
                                          double platform_impulse) const {
  const int n = layout_.n;
  // the kinetic energy jumps by p . (u + du / 2), p the generalized impulse
  double dT = 0.0;
  double dv = 0.0;
  if (has_platform_) {
    // [[M, c^T], [c, diag(I)]] [dv; dw] = [p_x; p]: platform first (Schur complement)
    double schur = 0.0, rhs = platform_impulse;
    angleTrig(th);
    for (int j = 0; j < n; ++j) {
      c_[j] = pend_[j].mL * cos_[j];
      schur += c_[j] * c_[j] * pend_[j].inv_inertia;
      rhs -= c_[j] * pend_[j].inv_inertia * pin_impulse[j];
    }
    dv = rhs / (mass_ - schur);
    dT += platform_impulse * (*v + 0.5 * dv);
    *v += dv;
  }
  for (int j = 0; j < n; ++j) {
    const double coupling = has_platform_ ? c_[j] * dv : 0.0;
    const double dw = (pin_impulse[j] - coupling) * pend_[j].inv_inertia;
    dT += pin_impulse[j] * (w[j] + 0.5 * dw);
    w[j] += dw;
  }
  return dT;
}

double MetronomeEquations::platformMobilityAt(const double* th) const {
  if (!has_platform_) return 0.0;
  double schur = 0.0;
  angleTrig(th);
  for (int j = 0; j < layout_.n; ++j) {
    const double c = pend_[j].mL * cos_[j];
    schur += c * c * pend_[j].inv_inertia;
  }
  return 1.0 / (mass_ - schur);
}

double MetronomeEquations::energyAt(double x, double v_in, const double* th,
                                    const double* w) const {
  const double v = has_platform_ ? v_in : 0.0;
  double e = 0.5 * mass_ * v * v + 0.5 * spring_ * x * x;
  for (int j = 0; j < layout_.n; ++j) {
    const PendulumConstants& p = pend_[j];
    const double co = std::cos(th[j]);
    e += p.mL * co * v * w[j] + 0.5 * p.inertia * w[j] * w[j] - p.mgL * co;
  }
  return e;
}

void MetronomeEquations::schurPass(const double* th, const double* w, double x, double& meff,
                                   double& G) const {
  angleTrig(th);
  const SchurSums sums = schurSums(layout_.n, mL_.data(), mgL_.data(), inv_inertia_.data(),
                                   damping_.data(), spring_, w, &x, sin_.data(), cos_.data(),
                                   c_.data(), r_.data(), g_term_.data(), s_term_.data());
  G = sums.G;
  meff = mass_ - sums.schur;
}

void MetronomeEquations::pendulumAccelerations(double a, double* dw) const {
  for (int j = 0; j < layout_.n; ++j) dw[j] = (r_[j] - c_[j] * a) * inv_inertia_[j];
}

double MetronomeEquations::dampingPower(const double* w) const {
  double power = 0.0;
  for (int j = 0; j < layout_.n; ++j) power += damping_[j] * w[j] * w[j];
  return power;
}

}  // namespace metrosync::direct
