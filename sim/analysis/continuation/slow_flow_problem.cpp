#include "sim/analysis/continuation/slow_flow_problem.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "base/constants.h"
#include "base/number_text.h"
#include "contact/law_registry.h"
#include "sim/analysis/continuation/border_stability.h"
#include "sim/analysis/continuation/branch.h"
#include "sim/analysis/continuation/derivatives.h"
#include "sim/analysis/continuation/lyapunov.h"

namespace metrosync::continuation {

namespace {

using Cd = std::complex<double>;
// The parameter cache holds a few hundred values: a Newton step and its differences use 3.
constexpr size_t kCacheSize = 256;

}  // namespace

SlowFlowProblem::SlowFlowProblem(const SlowFlowProblem& other)
    : SlowFlowProblem(other.params_at_, other.p0_, other.ref_) {}

SlowFlowProblem::SlowFlowProblem(ParamsAt params_at, double p0, int reference)
    : params_at_(std::move(params_at)), p0_(p0), ref_(reference) {
  const ScaledParams& sp = params(p0);
  n_ = static_cast<int>(sp.nu.size());
  for (int i = 0; i < n_; ++i)
    if (!sp.locked[i]) unlocked_.push_back(i);
  if (reference < 0 || reference >= n_ || sp.locked[reference])
    throw std::invalid_argument("the reference metronome must be an unlocked one");
  // the s borders exist for every Coulomb platform, also at mu = 0 (there the platform slips:
  // |Z| > mu), so that a continuation in mu starts from 0 or reaches it; the slow flow refuses
  // a static coefficient above the kinetic one before this (requireSlowFlow)
  coulomb_ = sp.friction.is(coulombLaw()) || sp.friction.is(staticCoulombLaw());
  fixed_ = sp.friction.is(fixedPlatformLaw());
  const int m = static_cast<int>(unlocked_.size());
  sys_.n = 2 * m;
  sys_.residual = [this](const Vec& x, double p, const Region& r) { return residual(x, p, r); };
  sys_.borders = [this](const Vec& x, double p) { return borders(x, p); };
  sys_.jumps = [m](int k) { return k < m; };
  sys_.eigenvalues = [this](const Vec& x, double p, const Region& r) {
    return eigenvalues(x, p, r);
  };
  sys_.lyapunov = [this](const Vec& x, double p, const Region& r) { return lyapunov(x, p, r); };
  sys_.stableOnBorder = [this](const Vec& x, double p) {
    return slowFlowReturns(params(p), unpack(x));
  };
  sys_.borderName = [this, m](int k) {
    if (k < m) return "A_" + std::to_string(unlocked_[k] + 1) + " = theta_c";
    return std::string(k == m ? "s = 1" : "s = sqrt(1 + pi^2/4)");
  };
}

const SlowFlowProblem::AtParameter& SlowFlowProblem::at(double p) const {
  auto it = cache_.find(p);
  if (it != cache_.end()) return it->second;
  if (cache_.size() > kCacheSize) cache_.clear();
  AtParameter a{params_at_(p), nullptr};
  try {
    a.flow = std::make_shared<const SlowFlow>(a.params);
  } catch (const std::invalid_argument&) {
    a.flow = nullptr;  // refused: NaN rates (rhs)
  }
  return cache_.emplace(p, std::move(a)).first->second;
}

const ScaledParams& SlowFlowProblem::params(double p) const {
  return at(p).params;
}

std::vector<Cd> SlowFlowProblem::rhs(double p, const Region& r, const std::vector<Cd>& z) const {
  const AtParameter& a = at(p);
  std::vector<Cd> dz(z.size(), Cd(std::numeric_limits<double>::quiet_NaN()));
  if (a.flow) a.flow->rhs(modes(r), z.data(), dz.data());
  return dz;
}

Vec SlowFlowProblem::pack(std::vector<Cd> z, double omega) const {
  const double a = std::abs(z[ref_]);
  const Cd rot = a > 0 ? std::conj(z[ref_]) / a : Cd(1.0);
  for (int i : unlocked_) z[i] *= rot;
  return packAsIs(z, omega);
}

Vec SlowFlowProblem::packAsIs(const std::vector<Cd>& z, double omega) const {
  Vec x(sys_.n);
  int k = 0;
  for (int i : unlocked_) {
    x(k++) = z[i].real();
    if (i != ref_) x(k++) = z[i].imag();
  }
  x(k) = omega;
  return x;
}

std::vector<Cd> SlowFlowProblem::unpack(const Vec& x) const {
  std::vector<Cd> z(n_, Cd(0.0));
  int k = 0;
  for (int i : unlocked_) {
    if (i == ref_) {
      z[i] = x(k++);
    } else {
      z[i] = Cd(x(k), x(k + 1));
      k += 2;
    }
  }
  return z;
}

SlowFlowModes SlowFlowProblem::modes(const Region& r) const {
  SlowFlowModes md;
  md.engaged.assign(n_, false);
  const int m = static_cast<int>(unlocked_.size());
  for (int k = 0; k < m; ++k) md.engaged[unlocked_[k]] = r[k] == 1;
  if (coulomb_)
    md.platform = r[m + 1] ? CoulombRegime::Slip
                  : r[m]   ? CoulombRegime::StickSlip
                           : CoulombRegime::Stuck;
  return md;
}

// G_i = f_i(z) - i Omega z_i (e3.1a-c in the rotating frame), real and imaginary parts.
Vec SlowFlowProblem::residual(const Vec& x, double p, const Region& r) const {
  const std::vector<Cd> z = unpack(x);
  const std::vector<Cd> f = rhs(p, r, z);
  const double om = omega(x);
  Vec G(sys_.n);
  int k = 0;
  for (int i : unlocked_) {
    const Cd g = f[i] - Cd(0, om) * z[i];
    G(k++) = g.real();
    G(k++) = g.imag();
  }
  return G;
}

double SlowFlowProblem::s(const Vec& x, double p) const {
  const ScaledParams& sp = params(p);
  Cd Z = 0;
  for (const Cd& zi : unpack(x)) Z += zi;
  const double mu = sp.friction.slowResponse().mu;  // 0 for a law without s
  return mu > 0 ? std::abs(Z) / mu : std::numeric_limits<double>::infinity();
}

Vec SlowFlowProblem::borders(const Vec& x, double p) const {
  const ScaledParams& sp = params(p);
  const std::vector<Cd> z = unpack(x);
  const int m = static_cast<int>(unlocked_.size());
  Vec b(m + (coulomb_ ? 2 : 0));
  for (int k = 0; k < m; ++k) b(k) = std::abs(z[unlocked_[k]]) - sp.theta_c[unlocked_[k]];
  if (coulomb_) {
    // |Z| - mu and |Z| - s_b mu: the signs of s - 1 and s - s_b, smooth through mu = 0
    Cd Z = 0;
    for (const Cd& zi : z) Z += zi;
    const double mu = sp.friction.valueOr("mu", 0.0);  // at this parameter value
    b(m) = std::abs(Z) - mu;
    b(m + 1) = std::abs(Z) - kCoulombSlipThreshold * mu;
  }
  return b;
}

CVec SlowFlowProblem::eigenvalues(const Vec& x, double p, const Region& r) const {
  return reducedJacobian(x, p, r).eigenvalues();
}

Mat SlowFlowProblem::reducedJacobian(const Vec& x, double p, const Region& r) const {
  // G as a function of all 2m real coordinates (Re z_i, Im z_i), Omega and the region held
  const double om = omega(x);
  const std::vector<Cd> z0 = unpack(x);
  const int m = static_cast<int>(unlocked_.size());
  auto G = [&](const Vec& u) {
    std::vector<Cd> z = z0;
    for (int k = 0; k < m; ++k) z[unlocked_[k]] = Cd(u(2 * k), u(2 * k + 1));
    const std::vector<Cd> f = rhs(p, r, z);
    Vec g(2 * m);
    for (int k = 0; k < m; ++k) {
      const Cd gk = f[unlocked_[k]] - Cd(0, om) * z[unlocked_[k]];
      g(2 * k) = gk.real(), g(2 * k + 1) = gk.imag();
    }
    return g;
  };
  Vec u(2 * m), v(2 * m);  // v = i z, the symmetry's direction: G'(u) v = i G(u) = 0
  for (int k = 0; k < m; ++k) {
    const Cd zk = z0[unlocked_[k]];
    u(2 * k) = zk.real(), u(2 * k + 1) = zk.imag();
    v(2 * k) = -zk.imag(), v(2 * k + 1) = zk.real();
  }
  const Mat J = jacobianOf(G, u);
  if (v.norm() == 0) return J;
  // orthonormal basis [v/|v|, U]: in it J is block triangular, the rest is U^T J U
  const Mat Q = Eigen::HouseholderQR<Mat>(v.normalized()).householderQ();
  const Mat U = Q.rightCols(2 * m - 1);
  return U.transpose() * J * U;
}

int SlowFlowProblem::referenceSlot() const {
  return static_cast<int>(std::find(unlocked_.begin(), unlocked_.end(), ref_) - unlocked_.begin());
}

// (A_k for every unlocked k, then phi_k - phi_r for k != r): 2m - 1 coordinates.
Vec SlowFlowProblem::polarState(const Vec& x) const {
  const std::vector<Cd> z = unpack(x);
  const int m = static_cast<int>(unlocked_.size()), kr = referenceSlot();
  Vec y(2 * m - 1);
  for (int k = 0, j = m; k < m; ++k) {
    y(k) = std::abs(z[unlocked_[k]]);
    if (k != kr) y(j++) = std::arg(z[unlocked_[k]]) - std::arg(z[ref_]);
  }
  return y;
}

Vec SlowFlowProblem::fromPolar(const Vec& y) const {
  std::vector<Cd> z(n_, Cd(0.0));
  const int m = static_cast<int>(unlocked_.size()), kr = referenceSlot();
  for (int k = 0, j = m; k < m; ++k) z[unlocked_[k]] = std::polar(y(k), k == kr ? 0.0 : y(j++));
  return pack(z, 0.0);
}

Vec SlowFlowProblem::polarRates(const Vec& y, double p, const Region& r) const {
  const int m = static_cast<int>(unlocked_.size()), kr = referenceSlot();
  std::vector<Cd> z(n_, Cd(0.0));
  std::vector<double> phase(m, 0.0);
  for (int k = 0, j = m; k < m; ++k) {
    phase[k] = k == kr ? 0.0 : y(j++);
    z[unlocked_[k]] = std::polar(y(k), phase[k]);
  }
  const std::vector<Cd> dz = rhs(p, r, z);
  // dA/dtau = Re(e^{-i phi} dz), dphi/dtau = Im(e^{-i phi} dz) / A, relative to the reference's
  std::vector<double> dphi(m);
  Vec out(2 * m - 1);
  for (int k = 0; k < m; ++k) {
    const Cd e = std::polar(1.0, -phase[k]) * dz[unlocked_[k]];
    out(k) = e.real();
    dphi[k] = e.imag() / y(k);
  }
  for (int k = 0, j = m; k < m; ++k)
    if (k != kr) out(j++) = dphi[k] - dphi[kr];
  return out;
}

// The reduced polar flow near the Hopf point, for the Lyapunov coefficient.
double SlowFlowProblem::lyapunov(const Vec& x, double p, const Region& r) const {
  for (const Cd& zi : unpack(x))
    if (std::abs(zi) == 0) return std::numeric_limits<double>::quiet_NaN();
  return firstLyapunovCoefficient([&](const Vec& w) { return polarRates(w, p, r); }, polarState(x));
}

double SlowFlowProblem::omegaGuess(double p, const std::vector<Cd>& z) const {
  const ScaledParams& sp = params(p);
  std::vector<Cd> f;
  try {
    f = slowFlowRhs(sp, z);
  } catch (const std::invalid_argument&) {
    return 0.0;
  }
  return z[ref_] == Cd(0) ? 0.0 : (f[ref_] / z[ref_]).imag();
}

std::vector<double> SlowFlowProblem::amplitudes(const Vec& x) const {
  std::vector<double> A;
  for (const Cd& zi : unpack(x)) A.push_back(std::abs(zi));
  return A;
}

std::vector<double> SlowFlowProblem::phaseDifferences(const Vec& x) const {
  const std::vector<Cd> z = unpack(x);
  std::vector<double> psi;
  for (int j = 1; j < n_; ++j) {
    double d = std::arg(z[0]) - std::arg(z[j]);
    while (d < -0.5 * kPi) d += 2 * kPi;
    while (d >= 1.5 * kPi) d -= 2 * kPi;
    psi.push_back(d);
  }
  return psi;
}

std::string SlowFlowProblem::ticking(const Region& r, double weight) const {
  std::string s;
  const std::string w = ":" + numberText(weight, 3);
  for (size_t k = 0; k < unlocked_.size(); ++k) {
    if (!r[k]) continue;
    s += (s.empty() ? "" : " ") + std::to_string(unlocked_[k] + 1);
    if (r[k] == kOnBorder) s += w;
  }
  return s.empty() ? "none" : s;
}

int SlowFlowProblem::metronomeOf(int k) const {
  return k < static_cast<int>(unlocked_.size()) ? unlocked_[k] : -1;
}

std::string SlowFlowProblem::familyCause(const Region& r, int neutral) const {
  const std::string phases = neutral == 1 ? "a phase difference" : "phase differences";
  if (fixed_)
    return "the platform is fixed: the metronomes are uncoupled, so " + phases + " is free";
  if (coulomb_ && !r[unlocked_.size()])
    return "the platform is stuck (s <= 1): the metronomes are uncoupled, so every " +
           std::string(neutral == 1 ? "phase difference" : "set of phase differences") +
           " keeping the platform stuck is a locked state";
  return "a continuum of locked states (" + std::to_string(neutral) +
         " zero eigenvalue(s) along it)";
}

std::string SlowFlowProblem::platform(const Region& r) const {
  if (!coulomb_) return "constant";
  return toString(modes(r).platform);
}

}  // namespace metrosync::continuation
