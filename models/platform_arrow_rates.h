// The arrow's fused pass (PlatformArrow::tableRates): its body, for the translation unit that
// instantiates it with N known to the compiler (models/network_equations.cpp, the single board's
// right-hand side). Inlined there whole, as the single rig's right-hand side always was (one call
// per evaluation from the stepper).
#pragma once

#include "models/platform_arrow.h"
#include "models/schur_sums.h"
#include "models/vector_trig.h"

namespace metrosync::network {

// The rates on scratch arrays of n values each (sn, cs: the angles' sin and cos; c, r, g_term,
// s_term: models/schur_sums.h): the stack's for a known N, the members' otherwise. Drag: a
// pendulum has air drag (without, the code there was before any had).
template <int N, bool Drag>
inline __attribute__((always_inline)) ArrowPower PlatformArrow::tableBody(
    const double* xv, const double* th, const double* w_in, PlatformMode mode, double* dxv,
    double* dth_out, double* dw_out, double* __restrict sn, double* __restrict cs,
    double* __restrict c, double* __restrict r, double* __restrict g_term,
    double* __restrict s_term) const {
  const int n = N > 0 ? N : n_;
  const double* __restrict w = w_in;
  double* __restrict dth = dth_out;
  double* __restrict dw = dw_out;
  const double* __restrict mL = mL_.data();
  const double* __restrict mgL = mgL_.data();
  const double* __restrict inv_I = inv_inertia_.data();
  const double* __restrict damp = damping_.data();
  const double* __restrict drag = drag_.data();
  const double v = xv[1];
  sinCos(th, sn, cs, n);
  ArrowPower power;
  for (int j = 0; j < n; ++j) power.damping += damp[j] * w[j] * w[j];
  if constexpr (Drag)
    for (int j = 0; j < n; ++j) power.damping += drag[j] * std::abs(w[j]) * w[j] * w[j];

  double a = 0.0;  // xddot
  const bool platform_moves = moves_ && !(friction_.setValued() && mode == PlatformMode::Stuck);
  if (platform_moves) {
    // pass 1: c_j, r_j and the platform's Schur-reduced equation Meff xddot = G + F
    const auto [G, schur] = detail::schurSums<Drag>(n, mL, mgL, inv_I, damp, drag, spring_, w, xv,
                                                    sn, cs, c, r, g_term, s_term);
    const double F = friction_.force(v, mode);  // the law's force (contact/platform_friction.h)
    power.friction = -F * v;                    // PlatformFriction::power
    a = (G + F) / (mass_ - schur);
    // pass 2: the pendulums
    for (int j = 0; j < n; ++j) dw[j] = (r[j] - c[j] * a) * inv_I[j];
  } else {
    // platform still (fixed, or stuck): each pendulum on its own
    for (int j = 0; j < n; ++j)
      dw[j] = detail::pendulumTorque<Drag>(mgL[j], sn[j], damp[j], w[j], Drag ? drag[j] : 0.0) *
              inv_I[j];
  }
  for (int j = 0; j < n; ++j) dth[j] = w[j];
  dxv[0] = platform_moves ? v : 0.0;
  dxv[1] = a;
  return power;
}

template <int N>
inline __attribute__((always_inline)) ArrowPower PlatformArrow::tableRates(
    const double* xv, const double* th, const double* w, PlatformMode mode, double* dxv,
    double* dth, double* dw) const {
  // air drag: with N unknown only (a board with it runs as kAnyN, direct_engine.cpp), out of
  // line; the rates with N known have no drag and stay the code they were before any had it
  if constexpr (N <= 0)
    if (__builtin_expect(drag_any_, 0)) return tableDragRates<N>(xv, th, w, mode, dxv, dth, dw);
  if constexpr (N > 0) {
    double sn[N], cs[N], c[N], r[N], g_term[N], s_term[N];
    return tableBody<N, false>(xv, th, w, mode, dxv, dth, dw, sn, cs, c, r, g_term, s_term);
  } else {
    return tableBody<N, false>(xv, th, w, mode, dxv, dth, dw, sin_.data(), cos_.data(), c_.data(),
                               r_.data(), g_term_.data(), s_term_.data());
  }
}

template <int N>
__attribute__((noinline)) ArrowPower PlatformArrow::tableDragRates(const double* xv,
                                                                   const double* th,
                                                                   const double* w,
                                                                   PlatformMode mode, double* dxv,
                                                                   double* dth, double* dw) const {
  if constexpr (N > 0) {
    double sn[N], cs[N], c[N], r[N], g_term[N], s_term[N];
    return tableBody<N, true>(xv, th, w, mode, dxv, dth, dw, sn, cs, c, r, g_term, s_term);
  } else {
    return tableBody<N, true>(xv, th, w, mode, dxv, dth, dw, sin_.data(), cos_.data(), c_.data(),
                              r_.data(), g_term_.data(), s_term_.data());
  }
}

}  // namespace metrosync::network
