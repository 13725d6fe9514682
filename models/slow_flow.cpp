// The slow flow's equations (see models/slow_flow.h): the right-hand side, its modes and switching
// functions, the polar form and the start. The integrator is sim/engines/slow_flow/.
#include "models/slow_flow.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "base/constants.h"

namespace metrosync {

namespace {

using cplx = std::complex<double>;

void requireFinite(double v, const char* what) {
  if (!std::isfinite(v))
    throw std::invalid_argument(std::string("slow flow: ") + what + " is not finite");
}

// v itself when it has n entries; n zeros when it may be empty and is
std::vector<double> sized(const std::vector<double>& v, int n, const char* what,
                          bool may_be_empty) {
  if (v.size() == static_cast<size_t>(n)) return v;
  if (may_be_empty && v.empty()) return std::vector<double>(n, 0.0);
  throw std::invalid_argument(std::string("slow flow: ") + what + " has " +
                              std::to_string(v.size()) + " entries, expected " + std::to_string(n));
}

std::vector<bool> lockedMask(const ScaledParams& p, int n) {
  if (p.locked.empty()) return std::vector<bool>(n, false);
  if (p.locked.size() == static_cast<size_t>(n)) return p.locked;
  throw std::invalid_argument("slow flow: locked has the wrong size");
}

void requireSize(size_t size, int n, const char* what) {
  if (size != static_cast<size_t>(n))
    throw std::invalid_argument(std::string("slow flow: ") + what + " has the wrong size");
}

}  // namespace

SlowFlow::SlowFlow(const ScaledParams& p) : n_(static_cast<int>(p.nu.size())) {
  if (n_ < 1) throw std::invalid_argument("slow flow: no metronomes");
  nu_ = sized(p.nu, n_, "nu", false);
  J_ = sized(p.J, n_, "J", false);
  theta_c_ = sized(p.theta_c, n_, "theta_c", false);
  alpha_ = sized(p.alpha, n_, "alpha", true);
  const std::vector<bool> locked = lockedMask(p, n_);
  for (int i = 0; i < n_; ++i) {
    requireFinite(nu_[i], "nu");
    requireFinite(J_[i], "J");
    requireFinite(theta_c_[i], "theta_c");
    requireFinite(alpha_[i], "alpha");
    if (theta_c_[i] < 0.0) throw std::invalid_argument("slow flow: theta_c < 0");
    if (!locked[i]) active_.push_back(i);
  }
  const std::vector<LawParameter>& keys = p.friction.parameters();
  for (std::size_t k = 0; k < keys.size(); ++k) requireFinite(p.friction.values()[k], keys[k].key);
  // the law's averaged response (contact/slow_response.h); a law without one is refused here
  const SlowResponse response = p.friction.slowResponse();
  if (!response.available()) throw std::invalid_argument("slow flow: " + response.why());
  if (response.mu() < 0.0) throw std::invalid_argument("slow flow: mu < 0");
  mu_ = response.mu();
  coulomb_regimes_ = response.hasRegimes();
  if (!coulomb_regimes_) constant_beta_ = response.at(1.0);  // A-independent for these laws
}

SlowFlow::cplx SlowFlow::drive(const cplx* z) const {
  cplx Z = 0.0;
  for (int i : active_) Z += z[i];
  return Z;
}

SlowFlowModes SlowFlow::modesAt(const cplx* z) const {
  SlowFlowModes m;
  m.engaged.assign(n_, false);
  for (int i : active_) m.engaged[i] = std::abs(z[i]) > theta_c_[i];
  m.platform = coulomb_regimes_ ? coulombRegime(std::abs(drive(z)) / mu_) : CoulombRegime::Stuck;
  return m;
}

AveragedResponse SlowFlow::betas(CoulombRegime regime, cplx Z) const {
  if (!coulomb_regimes_) return constant_beta_;
  return coulombResponseIn(regime, std::sqrt(std::norm(Z)) / mu_);  // |Z| (hypot is slower)
}

// dz_i/dtau (header, complex form of e3.1a-c), the modes held fixed
void SlowFlow::rhs(const SlowFlowModes& modes, const cplx* z, cplx* dz) const {
  const cplx Z = drive(z);
  const AveragedResponse b = betas(modes.platform, Z);
  const cplx coupling = cplx(-b.beta2, b.beta1) * Z;  // (i beta1 - beta2) Z
  for (int i = 0; i < n_; ++i) dz[i] = 0.0;
  for (int i : active_) {
    const double a2 = std::norm(z[i]);
    cplx d = coupling + cplx(-0.5 * nu_[i], 0.5 * alpha_[i] - a2 / 16.0) * z[i];
    if (modes.engaged[i] && J_[i] != 0.0) {
      const double a = std::sqrt(a2);
      if (a > 0.0) {
        const double r = theta_c_[i] / a;
        // sqrt(1 - r^2) is clamped at 0 below theta_c (the mode's continuation)
        const double root = r < 1.0 ? std::sqrt((1.0 - r) * (1.0 + r)) : 0.0;
        d += (J_[i] / kPi) * cplx(root, -r) * (z[i] / a);
      }
    }
    dz[i] = d;
  }
}

// e3.1a-c in polar form, with the paper's indicators at (A, phi)
SlowFlowPolarRates SlowFlow::polarRates(const std::vector<double>& A,
                                        const std::vector<double>& phi) const {
  requireSize(A.size(), n_, "A");
  requireSize(phi.size(), n_, "phi");
  cplx Z = 0.0;
  for (int i : active_) Z += std::polar(A[i], phi[i]);
  const AveragedResponse b = coulomb_regimes_ ? coulombResponse(std::abs(Z) / mu_) : constant_beta_;
  SlowFlowPolarRates r;
  r.dA.assign(n_, 0.0);
  r.dphi.assign(n_, 0.0);
  for (int i : active_) {
    const cplx w = Z * std::polar(1.0, -phi[i]);
    const bool on = A[i] > theta_c_[i];
    const double thc = theta_c_[i];
    const double esc_amp = on ? J_[i] / kPi * std::sqrt(1.0 - thc * thc / (A[i] * A[i])) : 0.0;
    const double esc_phase = on ? J_[i] / kPi * thc / A[i] : 0.0;
    r.dA[i] = -b.beta2 * w.real() - b.beta1 * w.imag() - 0.5 * nu_[i] * A[i] + esc_amp;
    r.dphi[i] = (b.beta1 * w.real() - b.beta2 * w.imag() - esc_phase - A[i] * A[i] * A[i] / 16.0 +
                 0.5 * alpha_[i] * A[i]) /
                A[i];
  }
  return r;
}

std::vector<SlowFlowSwitch> SlowFlow::switches(const cplx* z) const {
  std::vector<SlowFlowSwitch> sws;
  for (int i : active_)
    if (J_[i] != 0.0) sws.push_back({SlowFlowSwitch::Escapement, i, true});
  if (coulomb_regimes_) {
    sws.push_back({SlowFlowSwitch::PlatformSlip, -1, true});
    sws.push_back({SlowFlowSwitch::PlatformFullSlip, -1, true});
  }
  for (SlowFlowSwitch& sw : sws) sw.positive = switchValue(sw, z) > 0.0;
  return sws;
}

double SlowFlow::switchValue(const SlowFlowSwitch& sw, const cplx* z) const {
  switch (sw.kind) {
    case SlowFlowSwitch::Escapement:
      return std::norm(z[sw.i]) - theta_c_[sw.i] * theta_c_[sw.i];  // A_i^2 - theta_c^2
    case SlowFlowSwitch::PlatformSlip:
      return std::norm(drive(z)) - mu_ * mu_;  // s = 1
    case SlowFlowSwitch::PlatformFullSlip: {
      const double m = mu_ * kCoulombSlipThreshold;  // s = s_b
      return std::norm(drive(z)) - m * m;
    }
  }
  return 0.0;
}

SlowFlowModes SlowFlow::modesOf(const std::vector<SlowFlowSwitch>& switches) const {
  SlowFlowModes m;
  m.engaged.assign(n_, false);
  bool slip = false, full = false;
  for (const SlowFlowSwitch& sw : switches) {
    if (sw.kind == SlowFlowSwitch::Escapement) m.engaged[sw.i] = sw.positive;
    if (sw.kind == SlowFlowSwitch::PlatformSlip) slip = sw.positive;
    if (sw.kind == SlowFlowSwitch::PlatformFullSlip) full = sw.positive;
  }
  m.platform =
      !slip ? CoulombRegime::Stuck : (full ? CoulombRegime::Slip : CoulombRegime::StickSlip);
  return m;
}

// ---- the free functions -------------------------------------------------------------------------

std::vector<cplx> slowFlowStart(const ScaledParams& p) {
  const SlowFlow f(p);
  if (p.theta0.size() != static_cast<size_t>(f.size()) ||
      p.thetadot0.size() != static_cast<size_t>(f.size()))
    throw std::invalid_argument("slow flow: theta0/thetadot0 have the wrong size");
  std::vector<cplx> z(f.size(), 0.0);
  for (int i : f.active()) {
    requireFinite(p.theta0[i], "theta0");
    requireFinite(p.thetadot0[i], "thetadot0");
    z[i] = cplx(p.thetadot0[i], p.theta0[i]);  // A cos phi + i A sin phi
  }
  return z;
}

SlowFlowModes slowFlowModesAt(const ScaledParams& p, const std::vector<cplx>& z) {
  const SlowFlow f(p);
  requireSize(z.size(), f.size(), "z");
  return f.modesAt(z.data());
}

AveragedResponse slowFlowBetas(const ScaledParams& p, const SlowFlowModes& modes,
                               const std::vector<cplx>& z) {
  const SlowFlow f(p);
  requireSize(z.size(), f.size(), "z");
  return f.betas(modes.platform, f.drive(z.data()));
}

std::vector<cplx> slowFlowRhs(const ScaledParams& p, const SlowFlowModes& modes,
                              const std::vector<cplx>& z) {
  const SlowFlow f(p);
  requireSize(z.size(), f.size(), "z");
  requireSize(modes.engaged.size(), f.size(), "modes");
  std::vector<cplx> dz(f.size());
  f.rhs(modes, z.data(), dz.data());
  return dz;
}

std::vector<cplx> slowFlowRhs(const ScaledParams& p, const std::vector<cplx>& z) {
  return slowFlowRhs(p, slowFlowModesAt(p, z), z);
}

SlowFlowPolarRates slowFlowPolarRates(const ScaledParams& p, const std::vector<double>& A,
                                      const std::vector<double>& phi) {
  return SlowFlow(p).polarRates(A, phi);
}

}  // namespace metrosync
