// Pass 1 of a platform arrow's rates (models/platform_arrow.h), shared by its fused pass
// (models/platform_arrow_rates.h) and its Schur pass (models/platform_arrow.cpp).
#pragma once

namespace metrosync::network::detail {

// Pass 1 of the rates: c_j, r_j and the platform's sums on scratch arrays of n values each, the
// terms in vectorizable loops, then the sums in order:
//   G = -k x + sum_j (m_j L_j sin theta_j thetadot_j^2 - c_j r_j / I_j),
//   schur = sum_j c_j^2 / I_j.
// Plain pointers: inlined into PlatformArrow::tableBody() they keep its __restrict promises (and
// its code).
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
  double G = -spring * *x, schur = 0.0;  // x read here, as the rates always have
  for (int j = 0; j < n; ++j) {
    G += g_term[j];
    schur += s_term[j];
  }
  return {G, schur};
}

}  // namespace metrosync::network::detail
