#include "sim/engines/slow_flow/slow_flow_engine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>

namespace metrosync {
namespace {

using cplx = std::complex<double>;
constexpr double kPi = 3.141592653589793;

std::string fmtTau(double tau) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", tau);
  return buf;
}

// ---- the parameters the flow needs, checked once ---------------------------------------------

struct Flow {
  int n = 0;                                  // metronomes
  std::vector<int> active;                    // unlocked metronomes: the integrated ones, in order
  std::vector<double> nu, J, theta_c, alpha;  // (N x 1)
  std::vector<bool> locked;                   // (N x 1)
  bool coulomb_regimes = false;               // Coulomb with mu > 0: beta depends on s = |Z| / mu
  double mu = 0.0;
  AveragedResponse constant_beta;  // the response of every other law
};

void requireFinite(double v, const char* what) {
  if (!std::isfinite(v))
    throw std::invalid_argument(std::string("slow flow: ") + what + " is not finite");
}

Flow compileFlow(const ScaledParams& p) {
  Flow f;
  f.n = static_cast<int>(p.nu.size());
  if (f.n < 1) throw std::invalid_argument("slow flow: no metronomes");
  auto sized = [&](const std::vector<double>& v, const char* what, bool may_be_empty) {
    if (v.size() == static_cast<size_t>(f.n)) return v;
    if (may_be_empty && v.empty()) return std::vector<double>(f.n, 0.0);
    throw std::invalid_argument(std::string("slow flow: ") + what + " has " +
                                std::to_string(v.size()) + " entries, expected " +
                                std::to_string(f.n));
  };
  f.nu = sized(p.nu, "nu", false);
  f.J = sized(p.J, "J", false);
  f.theta_c = sized(p.theta_c, "theta_c", false);
  f.alpha = sized(p.alpha, "alpha", true);
  if (p.locked.empty()) {
    f.locked.assign(f.n, false);
  } else if (p.locked.size() == static_cast<size_t>(f.n)) {
    f.locked = p.locked;
  } else {
    throw std::invalid_argument("slow flow: locked has the wrong size");
  }
  for (int i = 0; i < f.n; ++i) {
    requireFinite(f.nu[i], "nu");
    requireFinite(f.J[i], "J");
    requireFinite(f.theta_c[i], "theta_c");
    requireFinite(f.alpha[i], "alpha");
    if (f.theta_c[i] < 0.0) throw std::invalid_argument("slow flow: theta_c < 0");
    if (!f.locked[i]) f.active.push_back(i);
  }
  requireFinite(p.mu, "mu");
  requireFinite(p.c, "c");
  if (p.mu < 0.0) throw std::invalid_argument("slow flow: mu < 0");
  f.mu = p.mu;
  f.coulomb_regimes = p.law == FrictionLaw::Coulomb && p.mu > 0.0;
  f.constant_beta = averagedResponse(p.law, p.mu, p.c, 1.0);  // A-independent for these laws
  return f;
}

cplx drive(const Flow& f, const cplx* z) {
  cplx Z = 0.0;
  for (int i : f.active) Z += z[i];
  return Z;
}

AveragedResponse betasOf(const Flow& f, CoulombRegime regime, cplx Z) {
  if (!f.coulomb_regimes) return f.constant_beta;
  return coulombResponseIn(regime, std::abs(Z) / f.mu);
}

// dz/dtau for all N metronomes (locked: 0), the modes held fixed
void rhsComplex(const Flow& f, const std::vector<bool>& engaged, CoulombRegime regime,
                const cplx* z, cplx* dz) {
  const cplx Z = drive(f, z);
  const AveragedResponse b = betasOf(f, regime, Z);
  const cplx coupling = cplx(-b.beta2, b.beta1) * Z;  // (i beta1 - beta2) Z
  for (int i = 0; i < f.n; ++i) dz[i] = 0.0;
  for (int i : f.active) {
    const double a2 = std::norm(z[i]);
    cplx d = coupling + cplx(-0.5 * f.nu[i], 0.5 * f.alpha[i] - a2 / 16.0) * z[i];
    if (engaged[i] && f.J[i] != 0.0) {
      const double a = std::sqrt(a2);
      if (a > 0.0) {
        const double r = f.theta_c[i] / a;
        // sqrt(1 - r^2) is clamped at 0 below theta_c (the mode's continuation)
        const double root = r < 1.0 ? std::sqrt((1.0 - r) * (1.0 + r)) : 0.0;
        d += (f.J[i] / kPi) * cplx(root, -r) * (z[i] / a);
      }
    }
    dz[i] = d;
  }
}

// ---- switching surfaces ------------------------------------------------------------------------

// An event function h(state) and the side the flow is on (sigma h >= 0 while in the mode).
struct Switch {
  enum Kind { Escapement, PlatformSlip, PlatformFullSlip } kind;
  int i = -1;  // metronome, for Escapement
  double sigma = 1.0;
};

double switchValue(const Flow& f, const Switch& sw, const cplx* z) {
  switch (sw.kind) {
    case Switch::Escapement:
      return std::norm(z[sw.i]) - f.theta_c[sw.i] * f.theta_c[sw.i];  // A_i^2 - theta_c^2
    case Switch::PlatformSlip:
      return std::norm(drive(f, z)) - f.mu * f.mu;  // s = 1
    case Switch::PlatformFullSlip: {
      const double m = f.mu * kCoulombSlipThreshold;  // s = s_b
      return std::norm(drive(f, z)) - m * m;
    }
  }
  return 0.0;
}

SlowFlowModes modesFromSwitches(const std::vector<Switch>& sws,
                                const std::vector<bool>& start_engaged) {
  SlowFlowModes m;
  m.engaged = start_engaged;
  bool slip = false, full = false;
  for (const Switch& sw : sws) {
    if (sw.kind == Switch::Escapement) m.engaged[sw.i] = sw.sigma > 0.0;
    if (sw.kind == Switch::PlatformSlip) slip = sw.sigma > 0.0;
    if (sw.kind == Switch::PlatformFullSlip) full = sw.sigma > 0.0;
  }
  m.platform =
      !slip ? CoulombRegime::Stuck : (full ? CoulombRegime::Slip : CoulombRegime::StickSlip);
  return m;
}

SlowFlowModes modesAt(const Flow& f, const cplx* z) {
  SlowFlowModes m;
  m.engaged.assign(f.n, false);
  for (int i : f.active) m.engaged[i] = std::abs(z[i]) > f.theta_c[i];
  m.platform =
      f.coulomb_regimes ? coulombRegime(std::abs(drive(f, z)) / f.mu) : CoulombRegime::Stuck;
  return m;
}

// ---- Dormand-Prince 5(4) with Hairer's dense output ----------------------------------------

// Knows nothing about metronomes: an autonomous system y' = F(y) of dimension n.
class Dopri5 {
 public:
  explicit Dopri5(int n)
      : n_(n),
        k_(7, std::vector<double>(n)),
        y0_(n),
        y1_(n),
        tmp_(n),
        cont_(5, std::vector<double>(n)) {}

  // One step of size h from y0 with k1 = F(y0); returns the scaled error norm (<= 1: accept).
  template <class F>
  double attempt(F&& rhs, const std::vector<double>& y0, const std::vector<double>& k1, double h,
                 double rtol, double atol) {
    static constexpr double a21 = 1.0 / 5.0;
    static constexpr double a31 = 3.0 / 40.0, a32 = 9.0 / 40.0;
    static constexpr double a41 = 44.0 / 45.0, a42 = -56.0 / 15.0, a43 = 32.0 / 9.0;
    static constexpr double a51 = 19372.0 / 6561.0, a52 = -25360.0 / 2187.0, a53 = 64448.0 / 6561.0,
                            a54 = -212.0 / 729.0;
    static constexpr double a61 = 9017.0 / 3168.0, a62 = -355.0 / 33.0, a63 = 46732.0 / 5247.0,
                            a64 = 49.0 / 176.0, a65 = -5103.0 / 18656.0;
    static constexpr double a71 = 35.0 / 384.0, a73 = 500.0 / 1113.0, a74 = 125.0 / 192.0,
                            a75 = -2187.0 / 6784.0, a76 = 11.0 / 84.0;
    static constexpr double e1 = 71.0 / 57600.0, e3 = -71.0 / 16695.0, e4 = 71.0 / 1920.0,
                            e5 = -17253.0 / 339200.0, e6 = 22.0 / 525.0, e7 = -1.0 / 40.0;
    h_ = h;
    y0_ = y0;
    k_[0] = k1;
    auto& k = k_;
    for (int i = 0; i < n_; ++i) tmp_[i] = y0[i] + h * a21 * k[0][i];
    rhs(tmp_.data(), k[1].data());
    for (int i = 0; i < n_; ++i) tmp_[i] = y0[i] + h * (a31 * k[0][i] + a32 * k[1][i]);
    rhs(tmp_.data(), k[2].data());
    for (int i = 0; i < n_; ++i)
      tmp_[i] = y0[i] + h * (a41 * k[0][i] + a42 * k[1][i] + a43 * k[2][i]);
    rhs(tmp_.data(), k[3].data());
    for (int i = 0; i < n_; ++i)
      tmp_[i] = y0[i] + h * (a51 * k[0][i] + a52 * k[1][i] + a53 * k[2][i] + a54 * k[3][i]);
    rhs(tmp_.data(), k[4].data());
    for (int i = 0; i < n_; ++i)
      tmp_[i] = y0[i] +
                h * (a61 * k[0][i] + a62 * k[1][i] + a63 * k[2][i] + a64 * k[3][i] + a65 * k[4][i]);
    rhs(tmp_.data(), k[5].data());
    for (int i = 0; i < n_; ++i)
      y1_[i] = y0[i] +
               h * (a71 * k[0][i] + a73 * k[2][i] + a74 * k[3][i] + a75 * k[4][i] + a76 * k[5][i]);
    rhs(y1_.data(), k[6].data());  // first stage of the next step (FSAL)
    double sum = 0.0;
    for (int i = 0; i < n_; ++i) {
      const double e = h * (e1 * k[0][i] + e3 * k[2][i] + e4 * k[3][i] + e5 * k[4][i] +
                            e6 * k[5][i] + e7 * k[6][i]);
      const double sk = atol + rtol * std::max(std::fabs(y0[i]), std::fabs(y1_[i]));
      sum += (e / sk) * (e / sk);
    }
    return n_ > 0 ? std::sqrt(sum / n_) : 0.0;
  }

  // Coefficients of the continuous extension of the last attempted step (Hairer & Wanner,
  // dopri5 contd5): y(theta) = c0 + theta (c1 + (1-theta) (c2 + theta (c3 + (1-theta) c4))).
  void prepareDense() {
    static constexpr double d1 = -12715105075.0 / 11282082432.0, d3 = 87487479700.0 / 32700410799.0,
                            d4 = -10690763975.0 / 1880347072.0,
                            d5 = 701980252875.0 / 199316789632.0, d6 = -1453857185.0 / 822651844.0,
                            d7 = 69997945.0 / 29380423.0;
    for (int i = 0; i < n_; ++i) {
      const double ydiff = y1_[i] - y0_[i];
      const double bspl = h_ * k_[0][i] - ydiff;
      cont_[0][i] = y0_[i];
      cont_[1][i] = ydiff;
      cont_[2][i] = bspl;
      cont_[3][i] = ydiff - h_ * k_[6][i] - bspl;
      cont_[4][i] = h_ * (d1 * k_[0][i] + d3 * k_[2][i] + d4 * k_[3][i] + d5 * k_[4][i] +
                          d6 * k_[5][i] + d7 * k_[6][i]);
    }
  }

  void dense(double theta, std::vector<double>& out) const {
    if (theta == 1.0) {
      out = y1_;
      return;
    }
    const double t1 = 1.0 - theta;
    out.resize(n_);
    for (int i = 0; i < n_; ++i)
      out[i] =
          cont_[0][i] +
          theta * (cont_[1][i] + t1 * (cont_[2][i] + theta * (cont_[3][i] + t1 * cont_[4][i])));
  }

  const std::vector<double>& y1() const { return y1_; }
  const std::vector<double>& k7() const { return k_[6]; }

 private:
  int n_;
  double h_ = 0.0;
  std::vector<std::vector<double>> k_;
  std::vector<double> y0_, y1_, tmp_;
  std::vector<std::vector<double>> cont_;
};

// Hairer & Wanner's starting step (hinit in dopri5), order 5.
template <class F>
double initialStep(F&& rhs, const std::vector<double>& y, const std::vector<double>& f0,
                   double rtol, double atol) {
  const size_t n = y.size();
  double d0 = 0.0, d1 = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double sk = atol + rtol * std::fabs(y[i]);
    d0 += (y[i] / sk) * (y[i] / sk);
    d1 += (f0[i] / sk) * (f0[i] / sk);
  }
  d0 = std::sqrt(d0 / n);
  d1 = std::sqrt(d1 / n);
  double h0 = (d0 < 1e-10 || d1 < 1e-10) ? 1e-6 : 0.01 * d0 / d1;
  std::vector<double> y1(n), f1(n);
  for (size_t i = 0; i < n; ++i) y1[i] = y[i] + h0 * f0[i];
  rhs(y1.data(), f1.data());
  double d2 = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double sk = atol + rtol * std::fabs(y[i]);
    d2 += ((f1[i] - f0[i]) / sk) * ((f1[i] - f0[i]) / sk);
  }
  d2 = std::sqrt(d2 / n) / h0;
  const double dm = std::max(d1, d2);
  const double h1 = dm <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / dm, 0.2);
  return std::min(100.0 * h0, h1);
}

// ---- envelope rows --------------------------------------------------------------------------

class RowWriter {
 public:
  RowWriter(const Flow& f, const ScaledParams& p, RunSink& sink) : f_(f), sink_(sink) {
    unwrap_.resize(f.n > 1 ? f.n - 1 : 0);
    last_phase_.assign(f.n, 0.0);
    for (int i = 0; i < f.n; ++i)
      if (i < static_cast<int>(p.theta0.size()) && i < static_cast<int>(p.thetadot0.size()))
        last_phase_[i] = std::atan2(p.theta0[i], p.thetadot0[i]);
  }

  EnvelopeRow make(double tau, const std::vector<cplx>& z) {
    EnvelopeRow row;
    row.tau = tau;
    row.A.assign(f_.n, 0.0);
    for (int i : f_.active) {
      row.A[i] = std::abs(z[i]);
      if (z[i] != 0.0) last_phase_[i] = std::arg(z[i]);
    }
    for (int j = 1; j < f_.n; ++j)
      row.psi.push_back(unwrap_[j - 1](last_phase_[0] - last_phase_[j]));
    row.r = orderParameter(row.A, row.psi);
    return row;
  }

  void emit(double tau, const std::vector<cplx>& z) {
    last_ = make(tau, z);
    sink_.envelopeRow(last_);
    ++count_;
  }

  long count() const { return count_; }
  const EnvelopeRow& last() const { return last_; }

 private:
  const Flow& f_;
  RunSink& sink_;
  std::vector<PhaseUnwrapper> unwrap_;
  std::vector<double> last_phase_;
  EnvelopeRow last_;
  long count_ = 0;
};

void unpack(const Flow& f, const std::vector<double>& y, std::vector<cplx>& z) {
  z.assign(f.n, 0.0);
  for (size_t m = 0; m < f.active.size(); ++m) z[f.active[m]] = cplx(y[2 * m], y[2 * m + 1]);
}

}  // namespace

// ---- public functions ---------------------------------------------------------------------------

std::vector<cplx> slowFlowStart(const ScaledParams& p) {
  const Flow f = compileFlow(p);
  if (p.theta0.size() != static_cast<size_t>(f.n) || p.thetadot0.size() != static_cast<size_t>(f.n))
    throw std::invalid_argument("slow flow: theta0/thetadot0 have the wrong size");
  std::vector<cplx> z(f.n, 0.0);
  for (int i : f.active) {
    requireFinite(p.theta0[i], "theta0");
    requireFinite(p.thetadot0[i], "thetadot0");
    z[i] = cplx(p.thetadot0[i], p.theta0[i]);  // A cos phi + i A sin phi
  }
  return z;
}

SlowFlowModes slowFlowModesAt(const ScaledParams& p, const std::vector<cplx>& z) {
  const Flow f = compileFlow(p);
  if (z.size() != static_cast<size_t>(f.n)) throw std::invalid_argument("slow flow: z size");
  return modesAt(f, z.data());
}

AveragedResponse slowFlowBetas(const ScaledParams& p, const SlowFlowModes& modes,
                               const std::vector<cplx>& z) {
  const Flow f = compileFlow(p);
  if (z.size() != static_cast<size_t>(f.n)) throw std::invalid_argument("slow flow: z size");
  return betasOf(f, modes.platform, drive(f, z.data()));
}

std::vector<cplx> slowFlowRhs(const ScaledParams& p, const SlowFlowModes& modes,
                              const std::vector<cplx>& z) {
  const Flow f = compileFlow(p);
  if (z.size() != static_cast<size_t>(f.n) || modes.engaged.size() != static_cast<size_t>(f.n))
    throw std::invalid_argument("slow flow: z or modes has the wrong size");
  std::vector<cplx> dz(f.n);
  rhsComplex(f, modes.engaged, modes.platform, z.data(), dz.data());
  return dz;
}

std::vector<cplx> slowFlowRhs(const ScaledParams& p, const std::vector<cplx>& z) {
  return slowFlowRhs(p, slowFlowModesAt(p, z), z);
}

SlowFlowPolarRates slowFlowPolarRates(const ScaledParams& p, const std::vector<double>& A,
                                      const std::vector<double>& phi) {
  const Flow f = compileFlow(p);
  if (A.size() != static_cast<size_t>(f.n) || phi.size() != static_cast<size_t>(f.n))
    throw std::invalid_argument("slow flow: A or phi has the wrong size");
  cplx Z = 0.0;
  for (int i : f.active) Z += std::polar(A[i], phi[i]);
  const AveragedResponse b =
      f.coulomb_regimes ? coulombResponse(std::abs(Z) / f.mu) : f.constant_beta;
  SlowFlowPolarRates r;
  r.dA.assign(f.n, 0.0);
  r.dphi.assign(f.n, 0.0);
  for (int i : f.active) {
    const cplx w = Z * std::polar(1.0, -phi[i]);
    const bool on = A[i] > f.theta_c[i];
    const double esc_amp =
        on ? f.J[i] / kPi * std::sqrt(1.0 - f.theta_c[i] * f.theta_c[i] / (A[i] * A[i])) : 0.0;
    const double esc_phase = on ? f.J[i] / kPi * f.theta_c[i] / A[i] : 0.0;
    r.dA[i] = -b.beta2 * w.real() - b.beta1 * w.imag() - 0.5 * f.nu[i] * A[i] + esc_amp;
    r.dphi[i] = (b.beta1 * w.real() - b.beta2 * w.imag() - esc_phase - A[i] * A[i] * A[i] / 16.0 +
                 0.5 * f.alpha[i] * A[i]) /
                A[i];
  }
  return r;
}

RunReport runSlowFlow(const ScaledParams& p, const SlowFlowOptions& opt, RunSink& sink) {
  const auto wall_start = std::chrono::steady_clock::now();
  const Flow f = compileFlow(p);
  if (!(p.epsilon > 0.0) || !std::isfinite(p.epsilon))
    throw std::invalid_argument("slow flow: epsilon must be > 0 (it sets the output grid)");
  if (!(opt.tau_end >= 0.0) || !std::isfinite(opt.tau_end))
    throw std::invalid_argument("slow flow: tau_end must be finite and >= 0");
  if (!(opt.rtol > 0.0) || !(opt.atol > 0.0))
    throw std::invalid_argument("slow flow: rtol and atol must be > 0");
  if (opt.max_steps < 1 || opt.storm_events < 1 || !(opt.storm_window >= 0.0))
    throw std::invalid_argument(
        "slow flow: max_steps, storm_events must be >= 1, "
        "storm_window >= 0");

  RunReport rep;
  rep.model = "slow";
  rep.engine = "slowflow";
  rep.integrator = "dopri5";
  rep.accuracy = opt.rtol;

  const std::vector<cplx> z0 = slowFlowStart(p);
  const int na = static_cast<int>(f.active.size());
  const int dim = 2 * na;
  std::vector<double> y(dim);
  for (int m = 0; m < na; ++m) {
    y[2 * m] = z0[f.active[m]].real();
    y[2 * m + 1] = z0[f.active[m]].imag();
  }
  std::vector<cplx> z;  // scratch, (N x 1)
  std::vector<cplx> dz(f.n);

  // switching surfaces and the modes they define
  std::vector<Switch> switches;
  for (int i : f.active)
    if (f.J[i] != 0.0) switches.push_back({Switch::Escapement, i, 1.0});
  if (f.coulomb_regimes) {
    switches.push_back({Switch::PlatformSlip, -1, 1.0});
    switches.push_back({Switch::PlatformFullSlip, -1, 1.0});
  }
  unpack(f, y, z);
  const SlowFlowModes start_modes = modesAt(f, z.data());
  for (Switch& sw : switches) sw.sigma = switchValue(f, sw, z.data()) > 0.0 ? 1.0 : -1.0;
  SlowFlowModes modes = modesFromSwitches(switches, start_modes.engaged);

  long rhs_evals = 0;
  std::vector<cplx> zs(f.n), dzs(f.n);
  auto rhs = [&](const double* yy, double* dy) {
    ++rhs_evals;
    for (int i = 0; i < f.n; ++i) zs[i] = 0.0;
    for (int m = 0; m < na; ++m) zs[f.active[m]] = cplx(yy[2 * m], yy[2 * m + 1]);
    rhsComplex(f, modes.engaged, modes.platform, zs.data(), dzs.data());
    for (int m = 0; m < na; ++m) {
      dy[2 * m] = dzs[f.active[m]].real();
      dy[2 * m + 1] = dzs[f.active[m]].imag();
    }
  };

  RowWriter rows(f, p, sink);
  long next_row = 0;
  auto emitRowsUpTo = [&](double tau_hi, double tau_lo, double h, const Dopri5* stepper) {
    std::vector<double> yr;
    for (;;) {
      const double tk = envelopeTau(p.epsilon, next_row);
      if (tk > tau_hi || tk > opt.tau_end) break;
      if (stepper != nullptr) {
        stepper->dense(std::min(1.0, std::max(0.0, (tk - tau_lo) / h)), yr);
      } else {
        yr = y;
      }
      unpack(f, yr, z);
      rows.emit(tk, z);
      ++next_row;
    }
  };

  auto finish = [&](bool complete, const std::string& why, double tau) {
    rep.complete = complete;
    rep.failure = why;
    rep.counts.rhs_evals = rhs_evals;
    if (rows.count() > 0) {
      rep.final_row = rows.last();
    } else {
      unpack(f, y, z);
      rep.final_row = rows.make(tau, z);
    }
    rep.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    return rep;
  };

  double tau = 0.0;
  if (dim == 0) {  // every metronome locked: nothing moves
    emitRowsUpTo(opt.tau_end, 0.0, 1.0, nullptr);
    return finish(true, "", opt.tau_end);
  }

  Dopri5 stepper(dim);
  std::vector<double> k1(dim), yd, ye;
  rhs(y.data(), k1.data());
  double h = std::min(initialStep(rhs, y, k1, opt.rtol, opt.atol), std::max(opt.tau_end, 1e-300));
  double facold = 1e-4;
  bool last_rejected = false;
  long attempts = 0;
  std::deque<double> recent_events;
  // step size controller (Hairer & Wanner's dopri5 defaults, with Lund stabilisation)
  constexpr double kSafe = 0.9, kFacMin = 0.2, kFacMax = 10.0, kBeta = 0.04;
  constexpr double kExpo1 = 0.2 - kBeta * 0.75;
  constexpr int kSamples = 8;  // dense-output samples per step when looking for a crossing

  while (tau < opt.tau_end) {
    if (++attempts > opt.max_steps)
      return finish(false,
                    "slow flow: more than " + std::to_string(opt.max_steps) +
                        " steps, stopped at tau = " + fmtTau(tau),
                    tau);
    const bool to_end = h >= opt.tau_end - tau;
    if (to_end) h = opt.tau_end - tau;
    const double err = stepper.attempt(rhs, y, k1, h, opt.rtol, opt.atol);
    const double h_min = 1e-14 * std::max(1.0, std::fabs(tau));
    if (!(err <= 1.0)) {  // rejected (NaN included)
      const double shrink =
          std::isfinite(err) ? std::min(1.0 / kFacMin, std::pow(err, kExpo1) / kSafe) : 10.0;
      h /= shrink;
      last_rejected = true;
      if (h < h_min)
        return finish(false, "slow flow: step size underflow at tau = " + fmtTau(tau), tau);
      continue;
    }
    // accepted: next step size
    double fac = std::pow(err, kExpo1) / std::pow(facold, kBeta);
    fac = std::max(1.0 / kFacMax, std::min(1.0 / kFacMin, fac / kSafe));
    double h_next = h / fac;
    if (last_rejected) h_next = std::min(h_next, h);
    facold = std::max(err, 1e-4);
    last_rejected = false;
    ++rep.counts.steps;
    stepper.prepareDense();
    const double tau_new = to_end ? opt.tau_end : tau + h;

    // the first switching surface crossed in this step, located on the dense output
    double theta_event = 2.0;
    int fired = -1;
    for (size_t e = 0; e < switches.size(); ++e) {
      const Switch& sw = switches[e];
      auto side = [&](double theta) {
        stepper.dense(theta, yd);
        unpack(f, yd, z);
        return sw.sigma * switchValue(f, sw, z.data());
      };
      double a = 0.0, fa = 0.0;  // sigma h >= 0 at the start of every step (invariant)
      double b = -1.0, fb = 0.0;
      for (int j = 1; j <= kSamples; ++j) {
        const double th = static_cast<double>(j) / kSamples;
        const double v = side(th);
        if (v < 0.0) {
          b = th;
          fb = v;
          break;
        }
        a = th;
        fa = v;
      }
      if (b < 0.0 || a >= theta_event) continue;
      // Illinois: fa >= 0 > fb
      const double tol = std::max(1e-15, 4e-16 * std::fabs(tau) / h);
      int kept = 0;
      for (int it = 0; it < 200 && b - a > tol; ++it) {
        double c = (a * fb - b * fa) / (fb - fa);
        if (!(c > a && c < b)) c = 0.5 * (a + b);
        const double fc = side(c);
        if (fc < 0.0) {
          b = c;
          fb = fc;
          if (kept == -1) fa *= 0.5;
          kept = -1;
        } else {
          a = c;
          fa = fc;
          if (kept == 1) fb *= 0.5;
          kept = 1;
        }
      }
      if (b < theta_event) {
        theta_event = b;  // the first point on the far side of the surface
        fired = static_cast<int>(e);
      }
    }

    if (fired < 0) {
      emitRowsUpTo(tau_new, tau, h, &stepper);
      tau = tau_new;
      y = stepper.y1();
      k1 = stepper.k7();
      h = h_next;
      for (double v : y)
        if (!std::isfinite(v))
          return finish(false, "slow flow: non-finite state at tau = " + fmtTau(tau), tau);
      continue;
    }

    // a switch: rows up to it from this step's dense output, then restart on its far side
    const double tau_event = tau + theta_event * h;
    emitRowsUpTo(tau_event, tau, h, &stepper);
    stepper.dense(theta_event, yd);  // on the far side by construction
    // a fresh step of the exact length is more accurate than the interpolant; keep it when it
    // also lands on the far side (it differs from the interpolant by ~ the local error)
    Switch& sw = switches[fired];
    stepper.attempt(rhs, y, k1, theta_event * h, opt.rtol, opt.atol);
    unpack(f, stepper.y1(), z);
    ye = (-sw.sigma * switchValue(f, sw, z.data()) > 0.0) ? stepper.y1() : yd;
    y = ye;
    tau = tau_event;
    for (double v : y)
      if (!std::isfinite(v))
        return finish(false, "slow flow: non-finite state at tau = " + fmtTau(tau), tau);
    sw.sigma = -sw.sigma;
    long flips = 1;
    unpack(f, y, z);
    for (Switch& other : switches) {  // simultaneous crossings
      if (other.sigma * switchValue(f, other, z.data()) < 0.0) {
        other.sigma = -other.sigma;
        ++flips;
      }
    }
    modes = modesFromSwitches(switches, modes.engaged);
    rep.counts.events += flips;
    for (long k = 0; k < flips; ++k) recent_events.push_back(tau);
    while (static_cast<int>(recent_events.size()) > opt.storm_events) recent_events.pop_front();
    if (static_cast<int>(recent_events.size()) == opt.storm_events &&
        recent_events.back() - recent_events.front() <=
            opt.storm_window * std::max(1.0, std::fabs(tau)))
      return finish(false,
                    "slow flow: event storm (" + std::to_string(opt.storm_events) +
                        " switches within " + fmtTau(recent_events.back() - recent_events.front()) +
                        ") at tau = " + fmtTau(tau),
                    tau);
    rhs(y.data(), k1.data());
    h = std::max(h_next, h_min);
  }
  return finish(true, "", tau);
}

}  // namespace metrosync
