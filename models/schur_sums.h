// Pass 1 of a platform arrow's rates (models/platform_arrow.h), shared by its fused pass
// (models/platform_arrow_rates.h) and its Schur pass (models/platform_arrow.cpp).
#pragma once

#include <cmath>

namespace metrosync::network::detail {

// Pass 1 of the rates: c_j, r_j and the platform's sums on scratch arrays of n values each, the
// terms in vectorizable loops, then the sums in order:
//   G = -k x + sum_j (m_j L_j sin theta_j thetadot_j^2 - c_j r_j / I_j),
//   schur = sum_j c_j^2 / I_j.
// Drag: the pendulums' air drag, r_j gets -c_j thetadot_j |thetadot_j| (drag: (n x 1) c_j);
// without it the same code as before there was any. Plain pointers: inlined into
// PlatformArrow::tableBody() they keep its __restrict promises (and its code).
struct SchurSums {
  double G, schur;
};

// The pendulum's own torque r_j = -m_j g L_j sin theta_j - nu-bar_j L_j^2 thetadot_j
// (- c_j thetadot_j |thetadot_j| with Drag).
template <bool Drag>
inline __attribute__((always_inline)) double pendulumTorque(double mgL, double sn, double damp,
                                                            double w, double drag) {
  if constexpr (Drag)
    return -mgL * sn - damp * w - drag * w * std::abs(w);
  else
    return -mgL * sn - damp * w;
}

template <bool Drag>
inline __attribute__((always_inline)) SchurSums schurSums(
    int n, const double* mL, const double* mgL, const double* inv_I, const double* damp,
    const double* drag, double spring, const double* w, const double* x, const double* sn,
    const double* cs, double* c, double* r, double* g_term, double* s_term) {
  for (int j = 0; j < n; ++j) {
    c[j] = mL[j] * cs[j];
    r[j] = pendulumTorque<Drag>(mgL[j], sn[j], damp[j], w[j], Drag ? drag[j] : 0.0);
    const double c_over_I = c[j] * inv_I[j];
    g_term[j] = mL[j] * sn[j] * w[j] * w[j] - c_over_I * r[j];
    s_term[j] = c_over_I * c[j];
  }
  double G = -spring * *x, schur = 0.0;  // x read here, as the rates always have
  for (int j = 0; j < n; ++j) {
    G += g_term[j];
    schur += s_term[j];
  }
  return {G, schur};
}

}  // namespace metrosync::network::detail
