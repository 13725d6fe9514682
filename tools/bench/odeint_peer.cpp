// The Boost.Odeint peer (see odeint_peer.h). Stages, top to bottom:
//   1. the equations e1.1a-c in scaled variables, the escapement impulse and the holding force
//   2. two step drivers behind one small interface: dopri5 with dense output, rkf78 on exact steps
//   3. the run: witnesses at each step's ends (and at a pendulum's turning point when it comes
//      near theta_c inside a step), root finding, the event's resolution, the envelope samples
#include "tools/bench/odeint_peer.h"

#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "base/constants.h"
#include "models/scaling.h"
#include "sim/record/envelope_quadrature.h"

namespace metrosync::bench {

bool odeintAvailable() {
  return true;
}

std::vector<std::string> odeintIntegratorNames() {
  return {"dopri5", "rkf78"};
}

namespace {

namespace ode = boost::numeric::odeint;
using State = std::vector<double>;

// Envelope samples per fast period: the direct engine's schedule, so the trapezoid sums match.
constexpr int kSamplesPerPeriod = 64;
// Ticks whose platform impulses cancel to this fraction of their sum leave the platform at rest
// (identical metronomes in exact antiphase); rounding of the impulse sum is ~1e-16 of it.
constexpr double kCancelTol = 1e-9;
// A turning point of theta_j inside a step is looked for on the exact solution only when the
// step's cubic Hermite estimate of it comes within this fraction of theta_c: the Hermite error on
// a step of at most a tenth of a period is ~4e-4 of the amplitude, far below it.
constexpr double kGrazeMargin = 0.02;
// Largest step: this fraction of the fastest oscillation, so a step holds at most one turning
// point of any angle.
constexpr double kMaxStepFraction = 0.1;
// An event storm (Zeno): this many events within kStormWindow fast periods ends the run.
constexpr long kStormEvents = 1000;
constexpr double kStormWindow = 1e-6;

// --- 1. the equations --------------------------------------------------------------------------

struct Pendulum {
  int rig_index = 0;
  double mL = 0, mgL = 0, inertia = 0, damping = 0;  // m L, m g L, I, nu-bar L^2 (SI)
  double theta_c = 0;                                // scaled: theta-bar_c / sqrt(eps)
  double impulse = 0;                                // J-bar (N m s)
};

struct TickResult {
  double dv_abs = 0;  // sum of |xdot jumps| of the ticking pendulums (scaled)
};

// State z (scaled): x, xdot, then theta_j, thetadot_j for each swinging pendulum.
class Equations {
 public:
  Equations(const Rig& rig, const ScaledParams& sp);
  int n() const { return static_cast<int>(pend_.size()); }
  int dim() const { return 2 + 2 * n(); }
  static int th(int j) { return 2 + 2 * j; }
  static int om(int j) { return 3 + 2 * j; }
  const Pendulum& pendulum(int j) const { return pend_[j]; }
  // the law has stick and slip (Coulomb's, and every set-valued law)
  bool coulomb() const { return platform_ && friction_.setValued(); }
  double staticBound() const { return friction_.bounds().staticBound(); }  // holding

  // dz/ds (s the scaled time) in the current platform mode.
  void rhs(const State& z, State& dz);
  // H: the force friction must supply to hold the platform still (N), with xdot = 0.
  double holdingForce(const State& z) { return -push(z); }
  // The escapement impulses side * J-bar_j of `ticks` ((pendulum, side)), all at once.
  TickResult applyTicks(State& z, const std::vector<std::pair<int, int>>& ticks);

  PlatformMode mode = PlatformMode::Stuck;
  long evals = 0;

 private:
  // G of e1.1c reduced to the platform: everything but friction (SI);
  // fills c_, r_ and schur_.
  double push(const State& z);

  std::vector<Pendulum> pend_;
  bool platform_;
  PlatformFriction friction_;  // the law at the normal force M g (SI): its force, its bounds
  double mass_, spring_ = 0;
  double a_, xs_, w0_;  // sqrt(eps), the platform's length scale (m), omega0 (1/s)
  std::vector<double> c_, r_;
  double schur_ = 0;
};

Equations::Equations(const Rig& rig, const ScaledParams& sp)
    : platform_(rig.platform.friction.platformMoves()),
      friction_(rig.platform.friction.platform(rig.totalMass() * rig.gravity_m_s2)),
      mass_(rig.totalMass()),
      a_(sp.angle_scale),
      xs_(sp.x_scale_m),
      w0_(1.0 / sp.time_scale_s) {
  const double g = rig.gravity_m_s2;
  for (int i = 0; i < static_cast<int>(rig.metronomes.size()); ++i) {
    const MetronomeSpec& m = rig.metronomes[i];
    if (m.locked) continue;  // its whole mass rides with the platform (in M)
    pend_.push_back({i, m.pendulum_mass_kg * m.length_m, m.pendulum_mass_kg * g * m.length_m,
                     m.inertia_kgm2, m.damping_kg_s * m.length_m * m.length_m, m.theta_c_rad / a_,
                     m.impulse_Nms});
  }
  spring_ = rig.platform.spring_N_m;
  c_.resize(pend_.size());
  r_.resize(pend_.size());
}

double Equations::push(const State& z) {
  double G = -spring_ * xs_ * z[0];
  schur_ = 0;
  for (int j = 0; j < n(); ++j) {
    const Pendulum& p = pend_[j];
    const double theta = a_ * z[th(j)], w = a_ * w0_ * z[om(j)];
    const double s = std::sin(theta), c = p.mL * std::cos(theta);
    // e1.1a: I thetaddot = r - c xddot, r = -m g L sin theta - nu-bar L^2 thetadot
    c_[j] = c;
    r_[j] = -p.mgL * s - p.damping * w;
    // e1.1c with thetaddot eliminated: (M - sum c^2 / I) xddot = G + F
    G += p.mL * s * w * w - c * r_[j] / p.inertia;
    schur_ += c * c / p.inertia;
  }
  return G;
}

void Equations::rhs(const State& z, State& dz) {
  ++evals;
  const bool moves = platform_ && !(coulomb() && mode == PlatformMode::Stuck);
  const double v = xs_ * w0_ * z[1];  // SI
  const double G = push(z);
  double xdd = 0;  // SI
  if (moves) {
    const double F = friction_.force(v, mode);  // the law's (contact/platform_friction.h)
    xdd = (G + F) / (mass_ - schur_);
  }
  const double w0sq = w0_ * w0_;
  for (int j = 0; j < n(); ++j) {
    dz[th(j)] = z[om(j)];
    dz[om(j)] = (r_[j] - c_[j] * xdd) / pend_[j].inertia / (a_ * w0sq);
  }
  dz[0] = moves ? z[1] : 0.0;
  dz[1] = xdd / (xs_ * w0sq);
}

TickResult Equations::applyTicks(State& z, const std::vector<std::pair<int, int>>& ticks) {
  TickResult out;
  std::vector<double> p(n(), 0.0);  // generalized impulse on each pin (N m s)
  for (const auto& [j, side] : ticks) p[j] += side * pend_[j].impulse;
  double dv = 0;  // SI
  if (platform_) {
    // [[M, c^T], [c, diag(I)]] [dv; dw] = [0; p]: the platform first (Schur complement)
    push(z);
    const double meff = mass_ - schur_;
    double sum = 0;
    for (const auto& [j, side] : ticks) {
      const double part = c_[j] * side * pend_[j].impulse / pend_[j].inertia;
      sum += part;
      out.dv_abs += std::abs(part) / meff / (xs_ * w0_);
    }
    dv = -sum / meff;
    z[1] += dv / (xs_ * w0_);
  }
  for (int j = 0; j < n(); ++j)
    z[om(j)] += (p[j] - (platform_ ? c_[j] : 0.0) * dv) / pend_[j].inertia / (a_ * w0_);
  return out;
}

// Odeint's system: a reference to the equations (odeint copies systems by value).
struct System {
  Equations* eq;
  void operator()(const State& z, State& dz, double /*s*/) const { eq->rhs(z, dz); }
};

// --- 2. step drivers ---------------------------------------------------------------------------

// One accepted step [s0, s1] at a time, the states at its ends, and the solution inside it.
class Driver {
 public:
  Driver(Equations& eq, double max_dt) : sys_{&eq}, dt_(max_dt) {}
  virtual ~Driver() = default;
  virtual void restart(const State& z, double s) = 0;
  // One accepted step from s1 to at most s_limit.
  virtual void advance(double s_limit) = 0;
  // True when steps must end on the envelope samples (no interpolant to sample from).
  virtual bool endsOnSamples() const = 0;
  // The solution at s in [s0, s1]. The last one computed is kept until the next call: the event
  // search asks for the same time again (each candidate is tried at the earliest event so far).
  const State& at(double s) {
    if (s == s1) return y1;
    if (s == s0) return y0;
    if (s != cached_s_) {
      cache_.resize(y1.size());
      solve(s, cache_);
      cached_s_ = s;
    }
    return cache_;
  }
  double s0 = 0, s1 = 0;
  State y0, y1;
  long steps = 0;

 protected:
  virtual void solve(double s, State& out) = 0;  // s inside (s0, s1)
  // a new step begins at the old one's end; the cache belongs to the old one
  void beginStep() {
    y0 = y1;
    s0 = s1;
    cached_s_ = std::numeric_limits<double>::quiet_NaN();
  }
  System sys_;
  double dt_;  // the step size the controller proposes next

 private:
  State cache_;
  double cached_s_ = std::numeric_limits<double>::quiet_NaN();
};

class Dopri5Driver : public Driver {
 public:
  Dopri5Driver(Equations& eq, double tol, double max_dt)
      : Driver(eq, max_dt),
        dense_(ode::make_dense_output(tol, tol, max_dt, ode::runge_kutta_dopri5<State>())) {}
  void restart(const State& z, double s) override {
    if (steps > 0) dt_ = dense_.current_time_step();
    dense_.initialize(z, s, dt_);
    y1 = z;
    s1 = s;
    beginStep();
  }
  void advance(double s_limit) override {
    beginStep();
    const auto span = dense_.do_step(sys_);
    ++steps;
    if (span.second <= s_limit) {
      s1 = span.second;
      y1 = dense_.current_state();
    } else {
      s1 = s_limit;
      dense_.calc_state(s_limit, y1);
    }
  }
  bool endsOnSamples() const override { return false; }

 private:
  void solve(double s, State& out) override { dense_.calc_state(s, out); }
  decltype(ode::make_dense_output(1.0, 1.0, 1.0, ode::runge_kutta_dopri5<State>())) dense_;
};

class Rkf78Driver : public Driver {
 public:
  Rkf78Driver(Equations& eq, double tol, double max_dt)
      : Driver(eq, max_dt),
        ctrl_(ode::make_controlled(tol, tol, max_dt, ode::runge_kutta_fehlberg78<State>())) {}
  void restart(const State& z, double s) override {
    y1 = z;
    s1 = s;
    beginStep();
  }
  void advance(double s_limit) override {
    beginStep();
    constexpr int kMaxTries = 500;
    for (int k = 0; k < kMaxTries; ++k) {
      const bool clipped = dt_ >= s_limit - s0;
      double dt = clipped ? s_limit - s0 : dt_, t = s0;
      y1 = y0;
      if (ctrl_.try_step(sys_, y1, t, dt) == ode::success) {
        ++steps;
        s1 = clipped ? s_limit : t;
        if (!clipped) dt_ = dt;  // a step cut short by a sample keeps the controller's size
        return;
      }
      dt_ = dt;
    }
    throw std::runtime_error("rkf78: no acceptable step in " + std::to_string(kMaxTries) +
                             " tries");
  }
  bool endsOnSamples() const override { return true; }

 private:
  // an exact step from the step's start
  void solve(double s, State& out) override { rk_.do_step(sys_, y0, s0, out, s - s0); }
  decltype(ode::make_controlled(1.0, 1.0, 1.0, ode::runge_kutta_fehlberg78<State>())) ctrl_;
  ode::runge_kutta_fehlberg78<State> rk_;
};

// --- 3. the run --------------------------------------------------------------------------------

// Root of g on [lo, hi], g(lo) < 0 <= g(hi), by Boost.Math's TOMS 748 (Alefeld, Potra and Shi:
// the bracketing method a Boost user reaches for) to a few ulps. Returns the bracket's upper end:
// there g >= 0, the event has happened.
template <class G>
double locate(G&& g, double lo, double g_lo, double hi, double g_hi) {
  constexpr std::uintmax_t kMaxIterations = 100;  // far more than a few ulps need
  std::uintmax_t iterations = kMaxIterations;
  return boost::math::tools::toms748_solve(g, lo, hi, g_lo, g_hi,
                                           boost::math::tools::eps_tolerance<double>(), iterations)
      .second;
}

// A witness rises through zero at its event: tick (j, side): side theta_j - theta_c,j; the
// platform: -mode xdot while slipping, |H| - bound while stuck.
struct Witness {
  int pendulum = -1;  // -1: the platform
  int side = 0;
};

struct Candidate {
  int witness = 0;
  double lo = 0, hi = 0;  // bracket of the crossing
  bool forced = false;    // a slip that never got going: stop it at hi
};

class PeerRun {
 public:
  PeerRun(const Rig& rig, RunSink& sink, const OdeintOptions& opt);
  RunReport run();

 private:
  double witness(const Witness& w, const State& z);
  void findCandidates();
  void addGraze(int index);
  void addSlipFromRest(int index);
  double locateEarliest();
  void resolve(State& z, const std::vector<std::pair<int, int>>& ticks, bool platform);
  void settleAtRest(State& z);
  void setMode(PlatformMode m) {
    if (m != eq_.mode) ++report_.counts.stick_slip;
    eq_.mode = m;
  }
  bool handleEvents();
  // the envelope: the exact average of the peer's own solution (sim/record/envelope_quadrature.h),
  // each smooth stretch [env_s_, s] of the current step evaluated at the quadrature's nodes
  void envelopeTo(double s);
  static double sampleTime(long k) { return static_cast<double>(k) * (kTwoPi / kSamplesPerPeriod); }
  void emitSamples(double s_limit, bool inclusive);
  // per rig metronome (locked: 0), scaled
  std::vector<double> angles(const State& z) const;
  std::vector<double> rates(const State& z) const;
  std::vector<double> makeRow(double s, const State& z) const;

  const Rig& rig_;
  RunSink& sink_;
  // the sink wants the envelope: samples are taken (and rkf78, without an interpolant, ends its
  // steps on them); otherwise the run takes none and the tolerance alone sets rkf78's steps
  bool record_;
  ScaledParams sp_;
  Equations eq_;
  EnvelopeQuadrature env_;
  double env_s_ = 0;  // where the envelope's stretches have reached
  std::unique_ptr<Driver> drv_;
  RunReport report_;
  std::vector<Witness> witnesses_;
  std::vector<double> g0_, g1_;  // witnesses at the step's ends
  std::vector<Candidate> found_;
  double s_end_ = 0;
  long k_sample_ = 1;
  long burst_ = 0;
  double burst_start_ = 0;
};

std::vector<bool> activeMetronomes(const Rig& rig) {
  std::vector<bool> a;
  for (const auto& m : rig.metronomes) a.push_back(!m.locked);
  return a;
}

PeerRun::PeerRun(const Rig& rig, RunSink& sink, const OdeintOptions& opt)
    : rig_(rig),
      sink_(sink),
      record_(sink.wantsEnvelope()),
      sp_(computeScaled(rig)),
      eq_(rig, sp_),
      env_(sp_.epsilon, activeMetronomes(rig), rig.sim.t_end_s * (1.0 / sp_.time_scale_s), sink) {
  // the largest step: a tenth of the fastest pendulum's (or the platform spring's) period
  const double w0 = 1.0 / sp_.time_scale_s;
  double fastest = kTwoPi;
  for (int j = 0; j < eq_.n(); ++j) {
    const Pendulum& p = eq_.pendulum(j);
    fastest = std::min(fastest, kTwoPi * std::sqrt(p.inertia / p.mgL) * w0);
  }
  if (rig.platform.friction.platformMoves() && rig.platform.spring_N_m > 0)
    fastest = std::min(fastest, kTwoPi * std::sqrt(rig.totalMass() / rig.platform.spring_N_m) * w0);
  const double max_dt = kMaxStepFraction * fastest;
  if (opt.stepper == "dopri5")
    drv_ = std::make_unique<Dopri5Driver>(eq_, opt.tolerance, max_dt);
  else if (opt.stepper == "rkf78")
    drv_ = std::make_unique<Rkf78Driver>(eq_, opt.tolerance, max_dt);
  else
    throw std::invalid_argument("odeint peer: unknown stepper '" + opt.stepper +
                                "' (dopri5, rkf78)");
  for (int j = 0; j < eq_.n(); ++j)
    if (eq_.pendulum(j).impulse > 0) witnesses_.push_back({j, +1}), witnesses_.push_back({j, -1});
  if (eq_.coulomb()) witnesses_.push_back({-1, 0});
  report_.model = "full";
  report_.engine = "odeint";
  report_.integrator = opt.stepper;
  report_.accuracy = opt.tolerance;
  report_.counts.escapements.assign(rig.metronomes.size(), 0);
  s_end_ = rig.sim.t_end_s * w0;
}

std::vector<double> PeerRun::angles(const State& z) const {
  std::vector<double> v(rig_.metronomes.size(), 0.0);
  for (int j = 0; j < eq_.n(); ++j) v[eq_.pendulum(j).rig_index] = z[Equations::th(j)];
  return v;
}

std::vector<double> PeerRun::rates(const State& z) const {
  std::vector<double> v(rig_.metronomes.size(), 0.0);
  for (int j = 0; j < eq_.n(); ++j) v[eq_.pendulum(j).rig_index] = z[Equations::om(j)];
  return v;
}

// The engines' trajectory row (sim/record/run_report.h) in the rig's units.
std::vector<double> PeerRun::makeRow(double s, const State& z) const {
  const bool scaled = rig_.units == Units::Scaled;
  const double w0 = 1.0 / sp_.time_scale_s;
  const double xs = scaled ? 1.0 : sp_.x_scale_m, as = scaled ? 1.0 : sp_.angle_scale;
  const double ts = scaled ? 1.0 : w0;
  std::vector<double> row = {s / ts, z[0] * xs, z[1] * xs * ts};
  const std::vector<double> th = angles(z), w = rates(z);
  for (size_t i = 0; i < th.size(); ++i) {
    row.push_back(th[i] * as);
    row.push_back(w[i] * as * ts);
  }
  const double v = z[1];
  row.push_back(eq_.coulomb() ? static_cast<int>(eq_.mode) : (v > 0 ? 1 : (v < 0 ? -1 : 0)));
  return row;
}

double PeerRun::witness(const Witness& w, const State& z) {
  if (w.pendulum >= 0)
    return w.side * z[Equations::th(w.pendulum)] - eq_.pendulum(w.pendulum).theta_c;
  if (eq_.mode == PlatformMode::Stuck) return std::abs(eq_.holdingForce(z)) - eq_.staticBound();
  return -static_cast<int>(eq_.mode) * z[1];
}

void PeerRun::findCandidates() {
  found_.clear();
  for (int k = 0; k < static_cast<int>(witnesses_.size()); ++k) {
    g0_[k] = witness(witnesses_[k], drv_->y0);
    g1_[k] = witness(witnesses_[k], drv_->y1);
    if (g0_[k] < 0 && g1_[k] >= 0)
      found_.push_back({k, drv_->s0, drv_->s1});
    else if (g0_[k] < 0 && witnesses_[k].pendulum >= 0)
      addGraze(k);
    else if (g0_[k] == 0 && g1_[k] > 0 && witnesses_[k].pendulum < 0 &&
             eq_.mode != PlatformMode::Stuck)
      addSlipFromRest(k);
  }
}

// Both ends below theta_c, but the pendulum turns inside the step: does it reach theta_c there?
void PeerRun::addGraze(int index) {
  const Witness& w = witnesses_[index];
  const int ith = Equations::th(w.pendulum), iom = Equations::om(w.pendulum);
  const double d0 = w.side * drv_->y0[iom], d1 = w.side * drv_->y1[iom];
  if (!(d0 > 0 && d1 < 0)) return;
  // the turning point's height from the cubic Hermite interpolant of the step's ends
  const double h = drv_->s1 - drv_->s0;
  const double p0 = w.side * drv_->y0[ith], p1 = w.side * drv_->y1[ith];
  double top = std::max(p0, p1);
  constexpr int kProbe = 32;
  for (int k = 1; k < kProbe; ++k) {
    const double u = static_cast<double>(k) / kProbe, v = 1 - u;
    top = std::max(top, (1 + 2 * u) * v * v * p0 + u * v * v * h * d0 + u * u * (3 - 2 * u) * p1 -
                            u * u * v * h * d1);
  }
  const double theta_c = eq_.pendulum(w.pendulum).theta_c;
  if (top < theta_c * (1 - kGrazeMargin)) return;
  // close: find the turning point on the solution itself
  auto falling = [&](double s) { return -w.side * drv_->at(s)[iom]; };
  const double s_top = locate(falling, drv_->s0, -d0, drv_->s1, -d1);
  if (witness(w, drv_->at(s_top)) >= 0) found_.push_back({index, drv_->s0, s_top});
}

// A slip starting from rest (xdot = 0 exactly) that ends the step going the wrong way: if it got
// under way first, the stop is where it comes back to zero; if not, it never started.
void PeerRun::addSlipFromRest(int index) {
  constexpr int kProbe = 8;
  const double h = drv_->s1 - drv_->s0;
  double prev = drv_->s0;
  bool dipped = false;
  for (int k = 1; k < kProbe; ++k) {
    const double s = drv_->s0 + h * k / kProbe;
    const double g = witness(witnesses_[index], drv_->at(s));
    if (g < 0) dipped = true, prev = s;
    if (dipped && g >= 0) {
      found_.push_back({index, prev, s});
      return;
    }
  }
  if (dipped)
    found_.push_back({index, prev, drv_->s1});
  else
    found_.push_back({index, drv_->s1, drv_->s1, true});
}

// The earliest crossing's time: each candidate bracketed only if it has crossed by the earliest
// one found so far.
double PeerRun::locateEarliest() {
  std::sort(found_.begin(), found_.end(),
            [](const Candidate& a, const Candidate& b) { return a.hi < b.hi; });
  double best = found_.front().hi;
  for (Candidate& c : found_) {
    if (c.forced || c.lo >= best) continue;
    const Witness& w = witnesses_[c.witness];
    auto g = [&](double s) { return witness(w, drv_->at(s)); };
    const double g_hi = g(std::min(best, c.hi));
    if (g_hi < 0) continue;  // crosses after the earliest so far
    const double g_lo = c.lo == drv_->s0 ? g0_[c.witness] : g(c.lo);
    c.hi = locate(g, c.lo, g_lo, std::min(best, c.hi), g_hi);
    best = std::min(best, c.hi);
  }
  return best;
}

void PeerRun::settleAtRest(State& z) {
  z[1] = 0.0;
  const double H = eq_.holdingForce(z);
  setMode(std::abs(H) < eq_.staticBound()
              ? PlatformMode::Stuck
              : (H > 0 ? PlatformMode::SlipNegative : PlatformMode::SlipPositive));
}

// Every tick of the instant together, then the platform's Coulomb rule on the resulting state.
void PeerRun::resolve(State& z, const std::vector<std::pair<int, int>>& ticks, bool platform) {
  if (!ticks.empty()) {
    for (const auto& t : ticks) ++report_.counts.escapements[eq_.pendulum(t.first).rig_index];
    const TickResult imp = eq_.applyTicks(z, ticks);
    if (eq_.coulomb()) {
      if (std::abs(z[1]) <= kCancelTol * imp.dv_abs)
        settleAtRest(z);
      else
        setMode(z[1] > 0 ? PlatformMode::SlipPositive : PlatformMode::SlipNegative);
    }
  }
  if (!eq_.coulomb() || !(platform || !ticks.empty())) return;
  if (eq_.mode == PlatformMode::Stuck) {
    const double H = eq_.holdingForce(z);
    if (std::abs(H) >= eq_.staticBound())  // the push has reached the bound: it breaks free
      setMode(H > 0 ? PlatformMode::SlipNegative : PlatformMode::SlipPositive);
  } else if (static_cast<int>(eq_.mode) * z[1] <= 0) {
    settleAtRest(z);  // the slip has come to rest
  }
}

// The envelope up to s_limit, and the sample grid (where rkf78 ends its steps) past it (or past
// it and at it, if inclusive).
void PeerRun::emitSamples(double s_limit, bool inclusive) {
  if (!record_) return;
  envelopeTo(s_limit);
  for (;; ++k_sample_) {
    const double s = sampleTime(k_sample_);
    if (!(s < s_end_ && (s < s_limit || (inclusive && s == s_limit)))) break;
  }
}

void PeerRun::envelopeTo(double s) {
  if (!record_ || !(s > env_s_)) return;
  env_.stretchAt(env_s_, s, [&](double t, double* theta, double* thetadot) {
    const State& z = drv_->at(t);
    for (int j = 0; j < eq_.n(); ++j) {
      theta[eq_.pendulum(j).rig_index] = z[Equations::th(j)];
      thetadot[eq_.pendulum(j).rig_index] = z[Equations::om(j)];
    }
  });
  env_s_ = s;
}

// The step [s0, s1] just taken: its events, if any, resolved (the driver restarted after them).
// Returns false when there were none.
bool PeerRun::handleEvents() {
  findCandidates();
  if (found_.empty()) return false;
  const double s_e = locateEarliest();
  emitSamples(s_e, false);
  State z = drv_->at(s_e);
  std::vector<std::pair<int, int>> ticks;
  bool platform = false;
  for (const Candidate& c : found_) {
    const Witness& w = witnesses_[c.witness];
    if (c.lo > s_e || (!c.forced && witness(w, z) < 0)) continue;
    if (w.pendulum < 0) {
      platform = true;
      continue;
    }
    const double theta = z[Equations::th(w.pendulum)], rate = z[Equations::om(w.pendulum)];
    if (theta * rate > 0 && std::find_if(ticks.begin(), ticks.end(), [&](const auto& t) {
                              return t.first == w.pendulum;
                            }) == ticks.end())
      ticks.emplace_back(w.pendulum, theta > 0 ? 1 : -1);
  }
  ++report_.counts.events;
  resolve(z, ticks, platform);  // the envelope's stretch ended at s_e (emitSamples above)
  drv_->restart(z, s_e);
  if (s_e - burst_start_ > kStormWindow * kTwoPi) burst_start_ = s_e, burst_ = 0;
  if (++burst_ > kStormEvents) throw std::runtime_error("event storm");
  return true;
}

RunReport PeerRun::run() {
  const auto wall0 = std::chrono::steady_clock::now();
  State z(eq_.dim(), 0.0);
  if (rig_.platform.friction.platformMoves()) z[0] = sp_.x0, z[1] = sp_.xdot0;
  for (int j = 0; j < eq_.n(); ++j) {
    z[Equations::th(j)] = sp_.theta0[eq_.pendulum(j).rig_index];
    z[Equations::om(j)] = sp_.thetadot0[eq_.pendulum(j).rig_index];
  }
  if (eq_.coulomb()) {
    if (z[1] == 0)
      settleAtRest(z);
    else
      eq_.mode = z[1] > 0 ? PlatformMode::SlipPositive : PlatformMode::SlipNegative;
    report_.counts.stick_slip = 0;  // the start is not a switch
  }
  g0_.resize(witnesses_.size());
  g1_.resize(witnesses_.size());
  if (record_) env_.start(angles(z).data(), rates(z).data());
  sink_.trajectoryRow(makeRow(0.0, z));
  drv_->restart(z, 0.0);
  try {
    while (drv_->s1 < s_end_) {
      const bool on_samples = record_ && drv_->endsOnSamples();
      drv_->advance(on_samples ? std::min(sampleTime(k_sample_), s_end_) : s_end_);
      for (double v : drv_->y1)
        if (!std::isfinite(v)) throw std::runtime_error("non-finite state");
      if (!handleEvents()) emitSamples(drv_->s1, true);
    }
  } catch (const std::exception& e) {
    report_.complete = false;
    std::ostringstream os;
    os << "simulation failed at t = " << drv_->s1 * sp_.time_scale_s << " s: " << e.what();
    report_.failure = os.str();
  }
  report_.final_trajectory_row = makeRow(drv_->s1, drv_->y1);
  sink_.trajectoryRow(report_.final_trajectory_row);
  if (record_) report_.final_row = env_.finish();
  report_.counts.steps = drv_->steps;
  report_.counts.rhs_evals = eq_.evals;
  report_.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return report_;
}

}  // namespace

RunReport runOdeintPeer(const Rig& rig, RunSink& sink, const OdeintOptions& options) {
  PeerRun run(rig, sink, options);
  return run.run();
}

}  // namespace metrosync::bench
