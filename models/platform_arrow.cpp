#include "models/platform_arrow.h"

#include <cmath>
#include <stdexcept>

#include "models/schur_sums.h"
#include "models/vector_trig.h"

namespace metrosync {

PlatformFriction platformFriction(const Rig& rig) {
  return rig.platform.friction.platform(rig.totalMass() * rig.gravity_m_s2);
}

}  // namespace metrosync

namespace metrosync::network {

PlatformArrow::PlatformArrow(const Rig& rig, const PlatformFriction& friction)
    : moves_(rig.platform.friction.platformMoves()), friction_(friction), mass_(rig.totalMass()) {
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
    p.drag = m.air_drag_Nms2;
    p.theta_c = m.theta_c_rad;
    p.impulse = m.impulse_Nms;
    pend_.push_back(p);
  }
  n_ = static_cast<int>(pend_.size());
  if (moves_) {
    if (!(mass_ > 0)) throw std::invalid_argument("the platform's total mass must be > 0");
    spring_ = rig.platform.spring_N_m;
  }
  for (const PendulumConstants& p : pend_) {
    mL_.push_back(p.mL);
    mgL_.push_back(p.mgL);
    inv_inertia_.push_back(p.inv_inertia);
    damping_.push_back(p.damping);
    drag_.push_back(p.drag);
    drag_any_ = drag_any_ || p.drag != 0.0;
  }
  for (auto* v : {&sin_, &cos_, &c_, &r_, &g_term_, &s_term_}) v->resize(n_);
}

void PlatformArrow::angleTrig(const double* th) const {
  sinCos(th, sin_.data(), cos_.data(), n_);
}

double PlatformArrow::tableHoldingForce(double x, const double* th, const double* w) const {
  angleTrig(th);
  double G = -spring_ * x;
  for (int j = 0; j < n_; ++j) {
    const PendulumConstants& p = pend_[j];
    const double s = sin_[j], co = cos_[j];
    const double r = drag_any_ ? detail::pendulumTorque<true>(p.mgL, s, p.damping, w[j], p.drag)
                               : detail::pendulumTorque<false>(p.mgL, s, p.damping, w[j], 0.0);
    G += p.mL * s * w[j] * w[j] - p.mL * co / p.inertia * r;
  }
  return -G;
}

double PlatformArrow::tableHoldingForceRate(const double* th, const double* w) const {
  // d/dt of G = sum_j [mL s w^2 - mL co r / I] - k x with xdot = xddot = 0,
  // w' = r / I, r' = -mgL co w - b w'
  angleTrig(th);
  double dG = 0.0;
  for (int j = 0; j < n_; ++j) {
    const PendulumConstants& p = pend_[j];
    const double s = sin_[j], co = cos_[j];
    const double r = drag_any_ ? detail::pendulumTorque<true>(p.mgL, s, p.damping, w[j], p.drag)
                               : detail::pendulumTorque<false>(p.mgL, s, p.damping, w[j], 0.0);
    const double dw = r / p.inertia;
    // (d/dt of -d w |w| is -2 d |w| w')
    const double dr = drag_any_
                          ? -p.mgL * co * w[j] - p.damping * dw - 2 * p.drag * std::abs(w[j]) * dw
                          : -p.mgL * co * w[j] - p.damping * dw;
    dG += p.mL * (co * w[j] * w[j] * w[j] + 2 * s * w[j] * dw) -
          p.mL / p.inertia * (-s * w[j] * r + co * dr);
  }
  return -dG;
}

double PlatformArrow::applyImpulse(const double* th, double* v, double* w,
                                   const double* pin_impulse, double platform_impulse) const {
  // the kinetic energy jumps by p . (u + du / 2), p the generalized impulse
  double dT = 0.0;
  double dv = 0.0;
  if (moves_) {
    // [[M, c^T], [c, diag(I)]] [dv; dw] = [p_x; p]: platform first (Schur complement)
    double schur = 0.0, rhs = platform_impulse;
    angleTrig(th);
    for (int j = 0; j < n_; ++j) {
      c_[j] = pend_[j].mL * cos_[j];
      schur += c_[j] * c_[j] * pend_[j].inv_inertia;
      rhs -= c_[j] * pend_[j].inv_inertia * pin_impulse[j];
    }
    dv = rhs / (mass_ - schur);
    dT += platform_impulse * (*v + 0.5 * dv);
    *v += dv;
  }
  for (int j = 0; j < n_; ++j) {
    const double coupling = moves_ ? c_[j] * dv : 0.0;
    const double dw = (pin_impulse[j] - coupling) * pend_[j].inv_inertia;
    dT += pin_impulse[j] * (w[j] + 0.5 * dw);
    w[j] += dw;
  }
  return dT;
}

double PlatformArrow::mobility(const double* th) const {
  if (!moves_) return 0.0;
  double schur = 0.0;
  angleTrig(th);
  for (int j = 0; j < n_; ++j) {
    const double c = pend_[j].mL * cos_[j];
    schur += c * c * pend_[j].inv_inertia;
  }
  return 1.0 / (mass_ - schur);
}

double PlatformArrow::energy(double x, double v_in, const double* th, const double* w) const {
  const double v = moves_ ? v_in : 0.0;
  double e = 0.5 * mass_ * v * v + 0.5 * spring_ * x * x;
  for (int j = 0; j < n_; ++j) {
    const PendulumConstants& p = pend_[j];
    const double co = std::cos(th[j]);
    e += p.mL * co * v * w[j] + 0.5 * p.inertia * w[j] * w[j] - p.mgL * co;
  }
  return e;
}

void PlatformArrow::schurPass(const double* th, const double* w, double x, double& meff,
                              double& G) const {
  angleTrig(th);
  const detail::SchurSums sums =
      drag_any_ ? detail::schurSums<true>(n_, mL_.data(), mgL_.data(), inv_inertia_.data(),
                                          damping_.data(), drag_.data(), spring_, w, &x,
                                          sin_.data(), cos_.data(), c_.data(), r_.data(),
                                          g_term_.data(), s_term_.data())
                : detail::schurSums<false>(n_, mL_.data(), mgL_.data(), inv_inertia_.data(),
                                           damping_.data(), nullptr, spring_, w, &x, sin_.data(),
                                           cos_.data(), c_.data(), r_.data(), g_term_.data(),
                                           s_term_.data());
  G = sums.G;
  meff = mass_ - sums.schur;
}

void PlatformArrow::pendulumAccelerations(double a, double* dw) const {
  for (int j = 0; j < n_; ++j) dw[j] = (r_[j] - c_[j] * a) * inv_inertia_[j];
}

double PlatformArrow::dampingPower(const double* w) const {
  double power = 0.0;
  for (int j = 0; j < n_; ++j) power += damping_[j] * w[j] * w[j];
  if (drag_any_)
    for (int j = 0; j < n_; ++j) power += drag_[j] * std::abs(w[j]) * w[j] * w[j];
  return power;
}

}  // namespace metrosync::network
