// The slow flow's locked states as a ContinuationSystem. A locked state rotates rigidly,
// z_i(tau) = z_i e^{i Omega tau}, so in the frame rotating at Omega it is a fixed point of
//   G_i(z, Omega) = f_i(z) - i Omega z_i = 0      (f = models/slow_flow.h's dz_i/dtau, e3.1a-c)
// for every unlocked metronome i: 2m real equations. The phase symmetry (f(e^{ic} z) = e^{ic}
// f(z)) is removed by rotating so that the reference metronome's z_r is real: the unknowns are
// Re z_r, (Re z_i, Im z_i) for i != r, and Omega: 2m in all. This form stays regular when an
// amplitude goes to 0 (unlike the polar form's 1/A_i), as long as z_r does not vanish (the
// reference is the metronome with the largest amplitude at the start).
//
// Borders: A_i = theta_c,i for each unlocked metronome (the escapement switches: a jump of the
// phase equation by J_i / (pi theta_c,i), so the branch is re-solved across it) and, on a Coulomb
// platform with mu > 0, s = |Z| / mu = 1 and s = s_b (kinks of beta1, beta2, eq. d2).
// Stability: eigenvalues of dG/dz (2m x 2m, Omega held) on the quotient by the symmetry's
// direction i z (an exact zero eigenvalue), i.e. the 2m - 1 eigenvalues of the reduced flow.
#pragma once

#include <complex>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "models/slow_flow.h"
#include "sim/analysis/continuation/system.h"

namespace metrosync::continuation {

// The slow flow's parameters at parameter value p (the rig with KEY = p, scaled).
using ParamsAt = std::function<ScaledParams(double p)>;

class SlowFlowProblem {
 public:
  // reference: the (unlocked, 0-based) metronome whose z is kept real.
  SlowFlowProblem(ParamsAt params_at, double p0, int reference);
  // The same problem with a cache of its own (one per thread: a problem is not thread-safe).
  SlowFlowProblem(const SlowFlowProblem& other);
  SlowFlowProblem& operator=(const SlowFlowProblem&) = delete;

  const ContinuationSystem& system() const { return sys_; }
  int metronomes() const { return n_; }
  int reference() const { return ref_; }

  // x from z (N x 1, rotated so that z_r is real and > 0) and Omega.
  Vec pack(std::vector<std::complex<double>> z, double omega) const;
  // x from z as it is (Im z_r dropped): unpack's inverse, also for a tangent's dz.
  Vec packAsIs(const std::vector<std::complex<double>>& z, double omega) const;
  std::vector<std::complex<double>> unpack(const Vec& x) const;  // (N x 1), 0 for locked
  double omega(const Vec& x) const { return x(x.size() - 1); }
  // Omega estimated from dz/dtau at a state close to a locked one: Im (f_r / z_r).
  double omegaGuess(double p, const std::vector<std::complex<double>>& z) const;

  // The output of a point: A_i (N x 1), psi_j = phi_1 - phi_j (N-1 x 1) in [-pi/2, 3 pi/2).
  std::vector<double> amplitudes(const Vec& x) const;
  std::vector<double> phaseDifferences(const Vec& x) const;
  // The region in words: the metronomes that tick (1-based; one on its threshold with the
  // weight of its escapement's formula, "2:0.47") and the platform's regime.
  std::string ticking(const Region& r,
                      double weight = std::numeric_limits<double>::quiet_NaN()) const;
  std::string platform(const Region& r) const;
  // The metronome (0-based) whose escapement switches at border k; -1 for a platform border.
  int metronomeOf(int k) const;
  // Why a neutral family exists in region r, in words.
  std::string familyCause(const Region& r, int neutral) const;
  double s(const Vec& x, double p) const;  // |Z| / mu (inf when mu = 0)

  SlowFlowModes modes(const Region& r) const;
  // dG/dz (Omega held) on the quotient by the symmetry's direction i z: (2m - 1) x (2m - 1), the
  // Jacobian of the reduced flow whose eigenvalues are the stability eigenvalues.
  Mat reducedJacobian(const Vec& x, double p, const Region& r) const;

  // The reduced polar flow (2m - 1 coordinates: A_k of every unlocked metronome, then the phases
  // phi_k - phi_r of the others), whose fixed points are the locked states and whose periodic
  // orbits are the slow flow's modulated (quasi-periodic) states. Singular where an A_k is 0.
  Vec polarState(const Vec& x) const;
  Vec fromPolar(const Vec& y) const;  // x with Omega = 0 (for borders and outputs)
  Vec polarRates(const Vec& y, double p, const Region& r) const;
  const ScaledParams& params(double p) const;

 private:
  Vec residual(const Vec& x, double p, const Region& r) const;
  Vec borders(const Vec& x, double p) const;
  CVec eigenvalues(const Vec& x, double p, const Region& r) const;
  double lyapunov(const Vec& x, double p, const Region& r) const;
  int referenceSlot() const;  // the reference's index among the unlocked

  // dz/dtau with region r's formulas; NaN where the parameters are refused (a value outside
  // the key's domain, e.g. mu < 0), so that the corrector fails there and the step control stays
  // out, and one-sided differences are taken at the edge.
  std::vector<std::complex<double>> rhs(double p, const Region& r,
                                        const std::vector<std::complex<double>>& z) const;

  // The parameters at p and their slow flow (checked once: null when refused).
  struct AtParameter {
    ScaledParams params;
    std::shared_ptr<const SlowFlow> flow;
  };
  const AtParameter& at(double p) const;

  ParamsAt params_at_;
  double p0_ = 0.0;
  mutable std::map<double, AtParameter> cache_;
  int n_ = 0;                  // metronomes
  std::vector<int> unlocked_;  // indices of the unlocked metronomes
  int ref_ = 0;                // the reference metronome
  bool coulomb_ = false;       // Coulomb platform: the s borders exist
  bool fixed_ = false;         // a fixed platform: the metronomes are uncoupled
  ContinuationSystem sys_;
};

}  // namespace metrosync::continuation
