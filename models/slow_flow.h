// The slow flow: e3.1a-c generalised to N metronomes (paper appendix "ab"; same per-metronome
// derivation, with the platform driven by Z = sum_j A_j e^{i phi_j}).
//
// With s = |Z| / mu, beta = (beta1, beta2)(s) the platform's averaged response
// (contact/averaged_response.h, any friction law) and w_i = Z e^{-i phi_i}:
//   dA_i/dtau        = -beta2 Re w_i - beta1 Im w_i - nu_i A_i / 2
//                      + (J_i/pi) sqrt(1 - theta_c,i^2 / A_i^2) [A_i > theta_c,i]
//   A_i dphi_i/dtau  =  beta1 Re w_i - beta2 Im w_i - (J_i/pi)(theta_c,i / A_i) [A_i > theta_c,i]
//                      - A_i^3 / 16 + alpha_i A_i / 2
// (for N = 2 and psi = phi_1 - phi_2 this is e3.1a-c). It is integrated in the complex amplitudes
// z_i = A_i e^{i phi_i}, free of the 1/A_i of the polar form:
//   dz_i/dtau = (i beta1 - beta2) Z + (-nu_i/2 + i (alpha_i/2 - |z_i|^2/16)) z_i
//               + (J_i/pi) (sqrt(1 - theta_c,i^2/A_i^2) - i theta_c,i/A_i) e^{i phi_i} [A_i >
//               theta_c,i]
// Locked metronomes (ScaledParams::locked) take no part: A = 0 throughout, not in Z. zeta and
// epsilon do not enter (they are O(epsilon) effects); epsilon only sets the output grid.
//
// The right-hand side switches where A_i crosses theta_c,i (escapement on/off: dphi_i/dtau jumps
// by J_i / (pi theta_c,i)) and has kinks where s crosses 1 and s_b = sqrt(1 + pi^2/4) (platform
// regime). The equations commute with a common rotation z_i -> z_i e^{i theta} (beta depends on
// |Z| only), which the integrator uses to step in a co-rotating frame. The integrator
// (sim/engines/slow_flow/) holds these modes fixed over a step, locates the crossings of the
// switching functions (SlowFlowSwitch) on the dense output and restarts there.
// Everything that says what the equations are lives here (models/slow_flow.cpp); the engine only
// steps, locates switches and writes rows.
#pragma once

#include <complex>
#include <vector>

#include "contact/averaged_response.h"
#include "models/scaling.h"

namespace metrosync {

// Which side of each switching surface the flow is on; the integrator holds these fixed over a
// step. The formulas are continued across the surface (see slowFlowRhs).
struct SlowFlowModes {
  std::vector<bool> engaged;                      // (N x 1) escapement term on: A_i > theta_c,i
  CoulombRegime platform = CoulombRegime::Stuck;  // Coulomb law with mu > 0 only
};

// The modes the paper's indicators give at z: engaged_i = |z_i| > theta_c,i, platform regime of
// s = |Z| / mu.
SlowFlowModes slowFlowModesAt(const ScaledParams& p, const std::vector<std::complex<double>>& z);

// beta1, beta2 for the drive Z = sum of unlocked z_i, with the platform regime of `modes`
// (Coulomb, mu > 0) or the law's constant response (viscous, none, fixed, Coulomb with mu = 0).
AveragedResponse slowFlowBetas(const ScaledParams& p, const SlowFlowModes& modes,
                               const std::vector<std::complex<double>>& z);

// dz_i/dtau, (N x 1); 0 for locked metronomes (whose z is ignored). With explicit modes the
// formulas continue across the switching surfaces: an engaged escapement below theta_c keeps its
// phase term and drops the (clamped) amplitude term; a disengaged one has no term; the platform
// regime's beta formula is used whatever s is (coulombResponseIn).
std::vector<std::complex<double>> slowFlowRhs(const ScaledParams& p, const SlowFlowModes& modes,
                                              const std::vector<std::complex<double>>& z);
// ... with the modes of the state itself (the paper's indicators).
std::vector<std::complex<double>> slowFlowRhs(const ScaledParams& p,
                                              const std::vector<std::complex<double>>& z);

// The polar form (dA_i/dtau, dphi_i/dtau), straight from the equations above with the paper's
// indicators; requires A_i > 0 for unlocked metronomes (locked: 0, 0).
struct SlowFlowPolarRates {
  std::vector<double> dA, dphi;  // (N x 1)
};
SlowFlowPolarRates slowFlowPolarRates(const ScaledParams& p, const std::vector<double>& A,
                                      const std::vector<double>& phi);

// The start: z_i = thetadot0_i + i theta0_i (A_i = sqrt(theta0^2 + thetadot0^2),
// phi_i = atan2(theta0, thetadot0)); 0 for locked metronomes.
std::vector<std::complex<double>> slowFlowStart(const ScaledParams& p);

// A switching function: value(z) changes sign where a mode changes.
//   Escapement i        A_i^2 - theta_c,i^2         (> 0: escapement engaged)
//   PlatformSlip        |Z|^2 - mu^2                 (> 0: s > 1, the platform slips part time)
//   PlatformFullSlip    |Z|^2 - (mu s_b)^2           (> 0: s > s_b, it slips all the time)
// `positive` is the side the flow is on; the integrator flips it where the function crosses 0.
struct SlowFlowSwitch {
  enum Kind { Escapement, PlatformSlip, PlatformFullSlip } kind = Escapement;
  int i = -1;  // metronome, for Escapement
  bool positive = true;
};

// The slow flow's parameters, checked once (throws std::invalid_argument on inconsistent sizes,
// non-finite values, theta_c < 0 or mu < 0). The free functions above are thin wrappers; an
// integrator keeps one for the whole run. z, dz: (N x 1), locked entries ignored / set to 0.
class SlowFlow {
 public:
  using cplx = std::complex<double>;
  explicit SlowFlow(const ScaledParams& p);

  int size() const { return n_; }
  const std::vector<int>& active() const { return active_; }  // the unlocked metronomes

  cplx drive(const cplx* z) const;  // Z = sum of the unlocked z_i
  SlowFlowModes modesAt(const cplx* z) const;
  AveragedResponse betas(CoulombRegime regime, cplx Z) const;
  void rhs(const SlowFlowModes& modes, const cplx* z, cplx* dz) const;
  SlowFlowPolarRates polarRates(const std::vector<double>& A, const std::vector<double>& phi) const;

  // The switching functions (one per escapement with J_i != 0, two for Coulomb with mu > 0), on
  // the sides the state z is on.
  std::vector<SlowFlowSwitch> switches(const cplx* z) const;
  double switchValue(const SlowFlowSwitch& sw, const cplx* z) const;
  // The modes the switches' sides say (metronomes without a switch: not engaged, no term).
  SlowFlowModes modesOf(const std::vector<SlowFlowSwitch>& switches) const;

 private:
  int n_ = 0;
  std::vector<int> active_;
  std::vector<double> nu_, J_, theta_c_, alpha_;  // (N x 1)
  bool coulomb_regimes_ = false;  // Coulomb with mu > 0: beta depends on s = |Z| / mu
  double mu_ = 0.0;
  AveragedResponse constant_beta_;  // the response of every other law
};

}  // namespace metrosync
