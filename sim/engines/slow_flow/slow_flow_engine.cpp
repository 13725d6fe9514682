// The slow flow's integration loop: models/slow_flow.h says what the equations, modes and switching
// functions are; this file steps them with the shared ODE toolkit (sim/ode: the dopri5 tableau,
// its step-size control, dense output and Illinois root finding), holds the modes fixed over a
// step, locates the first switch crossed on the dense output, restarts there, and writes rows.
#include "sim/engines/slow_flow/slow_flow_engine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <stdexcept>
#include <string>

#include "sim/ode/rk_stepper.h"
#include "sim/ode/root_find.h"

namespace metrosync {
namespace {

using cplx = std::complex<double>;

// dense-output samples per step when looking for a sign change of a switching function: a
// function that crosses 0 twice within 1/8 of a step is missed, which the step control makes
// rare (the state moves by ~rtol^(1/5) of itself per step)
constexpr int kSwitchSamples = 8;
// a step shorter than this (times max(1, tau)) cannot move tau in double precision any more
constexpr double kMinStepRelative = 1e-14;
// shrink factor after a step that produced a non-finite state (no error estimate to go by)
constexpr double kNonFiniteShrink = 10.0;

std::string fmtTau(double tau) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", tau);
  return buf;
}

void checkOptions(const ScaledParams& p, const SlowFlowOptions& opt) {
  if (!(p.epsilon > 0.0) || !std::isfinite(p.epsilon))
    throw std::invalid_argument("slow flow: epsilon must be > 0 (it sets the output grid)");
  if (!(opt.tau_end >= 0.0) || !std::isfinite(opt.tau_end))
    throw std::invalid_argument("slow flow: tau_end must be finite and >= 0");
  if (!(opt.rtol > 0.0) || !(opt.atol > 0.0))
    throw std::invalid_argument("slow flow: rtol and atol must be > 0");
  if (opt.max_steps < 1 || opt.storm_events < 1 || !(opt.storm_window >= 0.0))
    throw std::invalid_argument(
        "slow flow: max_steps, storm_events must be >= 1, storm_window >= 0");
}

// The flow in the stepper's real coordinates y = (Re z_a, Im z_a) over the unlocked a, with the
// modes held fixed.
struct FlowRhs : ode::OdeRhs {
  explicit FlowRhs(const SlowFlow& flow) : f(flow), zs(flow.size()), dzs(flow.size()) {}

  void unpack(const double* y, std::vector<cplx>& z) const {
    z.assign(f.size(), 0.0);
    const auto& act = f.active();
    for (size_t m = 0; m < act.size(); ++m) z[act[m]] = cplx(y[2 * m], y[2 * m + 1]);
  }
  void eval(const double* y, double* dy) override {
    ++evaluations;
    unpack(y, zs);
    f.rhs(modes, zs.data(), dzs.data());
    const auto& act = f.active();
    for (size_t m = 0; m < act.size(); ++m) {
      dy[2 * m] = dzs[act[m]].real();
      dy[2 * m + 1] = dzs[act[m]].imag();
    }
  }

  const SlowFlow& f;
  SlowFlowModes modes;
  long evaluations = 0;
  std::vector<cplx> zs, dzs;
};

// Envelope rows from the complex amplitudes: A_i = |z_i|, psi_j = phi_1 - phi_j unwrapped (a
// metronome at A = 0 keeps its last phase, at first the start's).
class RowWriter {
 public:
  RowWriter(const SlowFlow& f, const ScaledParams& p, RunSink& sink) : f_(f), sink_(sink) {
    unwrap_.resize(f.size() > 1 ? f.size() - 1 : 0);
    last_phase_.assign(f.size(), 0.0);
    for (int i = 0; i < f.size(); ++i)
      if (i < static_cast<int>(p.theta0.size()) && i < static_cast<int>(p.thetadot0.size()))
        last_phase_[i] = std::atan2(p.theta0[i], p.thetadot0[i]);
  }

  const EnvelopeRow& emit(double tau, const std::vector<cplx>& z) {
    last_.tau = tau;
    last_.A.assign(f_.size(), 0.0);
    for (int i : f_.active()) {
      last_.A[i] = std::abs(z[i]);
      if (z[i] != 0.0) last_phase_[i] = std::arg(z[i]);
    }
    last_.psi.clear();
    for (int j = 1; j < f_.size(); ++j)
      last_.psi.push_back(unwrap_[j - 1](last_phase_[0] - last_phase_[j]));
    last_.r = orderParameter(last_.A, last_.psi);
    sink_.envelopeRow(last_);
    return last_;
  }

 private:
  const SlowFlow& f_;
  RunSink& sink_;
  std::vector<PhaseUnwrapper> unwrap_;
  std::vector<double> last_phase_;
  EnvelopeRow last_;
};

// Fails the run when storm_events switches fall within storm_window * max(1, tau).
class StormGuard {
 public:
  explicit StormGuard(const SlowFlowOptions& opt) : opt_(opt) {}
  // Records `count` switches at tau; the failure message, or empty.
  std::string add(double tau, long count) {
    for (long k = 0; k < count; ++k) recent_.push_back(tau);
    while (static_cast<int>(recent_.size()) > opt_.storm_events) recent_.pop_front();
    const double span = recent_.back() - recent_.front();
    if (static_cast<int>(recent_.size()) < opt_.storm_events ||
        span > opt_.storm_window * std::max(1.0, std::fabs(tau)))
      return "";
    return "slow flow: event storm (" + std::to_string(opt_.storm_events) + " switches within " +
           fmtTau(span) + ") at tau = " + fmtTau(tau);
  }

 private:
  const SlowFlowOptions& opt_;
  std::deque<double> recent_;
};

class SlowFlowRun {
 public:
  SlowFlowRun(const ScaledParams& p, const SlowFlowOptions& opt, RunSink& sink);
  RunReport run();

 private:
  struct Crossing {
    int fired = -1;      // the switch crossed first, -1: none
    double tau = 0.0;    // where: the first point on its far side
    double theta = 0.0;  // (tau - tau_) / h
  };
  std::string step(double& h);  // one attempted step; a failure message, or empty
  Crossing firstCrossing(double h);
  std::string crossSwitch(const Crossing& c, double h);
  void emitRowsUpTo(double tau_hi, double h);
  RunReport finish(const std::string& failure);

  const ScaledParams& p_;
  const SlowFlowOptions& opt_;
  std::chrono::steady_clock::time_point wall0_ = std::chrono::steady_clock::now();
  SlowFlow flow_;
  FlowRhs rhs_;
  ode::RkStepper stepper_;
  RowWriter rows_;
  StormGuard storm_;
  std::vector<SlowFlowSwitch> switches_;
  RunReport rep_;
  double tau_ = 0.0;
  long next_row_ = 0;
  long attempts_ = 0;
  bool last_rejected_ = false;
  std::vector<double> y_;
  std::vector<cplx> z_;
  std::vector<std::vector<cplx>> samples_;  // the dense output at th = j / kSwitchSamples
};

SlowFlowRun::SlowFlowRun(const ScaledParams& p, const SlowFlowOptions& opt, RunSink& sink)
    : p_(p),
      opt_(opt),
      flow_(p),
      rhs_(flow_),
      stepper_(ode::rkTableau("dopri5"), 2 * static_cast<int>(flow_.active().size()), rhs_),
      rows_(flow_, p, sink),
      storm_(opt),
      samples_(kSwitchSamples + 1) {
  checkOptions(p, opt);
  rep_.model = "slow";
  rep_.engine = "slowflow";
  rep_.integrator = stepper_.tableau().name;
  rep_.accuracy = opt.rtol;
  z_ = slowFlowStart(p);
  for (int i : flow_.active()) {
    y_.push_back(z_[i].real());
    y_.push_back(z_[i].imag());
  }
  switches_ = flow_.switches(z_.data());
  rhs_.modes = flow_.modesOf(switches_);
  stepper_.setTolerances(opt.rtol, std::vector<double>(y_.size(), opt.atol));
  stepper_.setNorm(ode::RkStepper::Norm::Rms);  // as DOPRI5 and the slow flow always did
}

// Grid rows tau_k <= min(tau_hi, tau_end), from the attempted step's dense output when h > 0.
void SlowFlowRun::emitRowsUpTo(double tau_hi, double h) {
  std::vector<double> yr(y_.size());
  for (;;) {
    const double tk = envelopeTau(p_.epsilon, next_row_);
    if (tk > tau_hi || tk > opt_.tau_end) break;
    if (h > 0.0)
      stepper_.interpolate(std::clamp((tk - tau_) / h, 0.0, 1.0), yr.data());
    else
      yr = y_;
    rhs_.unpack(yr.data(), z_);
    rows_.emit(tk, z_);
    ++next_row_;
  }
}

RunReport SlowFlowRun::run() {
  rows_.emit(0.0, z_);  // the start's envelope
  if (y_.empty()) {     // every metronome locked: nothing moves
    emitRowsUpTo(opt_.tau_end, 0.0);
    tau_ = opt_.tau_end;
    return finish("");
  }
  stepper_.restart(0.0, y_.data());
  double h = stepper_.initialStepSize(std::max(opt_.tau_end, 1e-300));
  while (tau_ < opt_.tau_end) {
    const std::string failure = step(h);
    if (!failure.empty()) return finish(failure);
  }
  return finish("");
}

std::string SlowFlowRun::step(double& h) {
  if (++attempts_ > opt_.max_steps)
    return "slow flow: more than " + std::to_string(opt_.max_steps) +
           " steps, stopped at tau = " + fmtTau(tau_);
  const bool to_end = h >= opt_.tau_end - tau_;
  if (to_end) h = opt_.tau_end - tau_;
  const double err = stepper_.attempt(h);
  if (!(err <= 1.0)) {  // rejected (a NaN included)
    h = std::isfinite(err) ? stepper_.nextStepSize(h, err, false) : h / kNonFiniteShrink;
    last_rejected_ = true;
    if (h < kMinStepRelative * std::max(1.0, std::fabs(tau_)))
      return "slow flow: step size underflow at tau = " + fmtTau(tau_);
    return "";
  }
  double h_next = stepper_.nextStepSize(h, err, true);
  if (last_rejected_) h_next = std::min(h_next, h);  // no growth right after a rejection
  last_rejected_ = false;
  ++rep_.counts.steps;
  const Crossing c = firstCrossing(h);
  if (c.fired >= 0) {
    const std::string failure = crossSwitch(c, h);
    h = std::max(h_next, kMinStepRelative * std::max(1.0, std::fabs(tau_)));
    return failure;
  }
  const double tau_new = to_end ? opt_.tau_end : tau_ + h;
  emitRowsUpTo(tau_new, h);
  stepper_.advance();
  tau_ = tau_new;
  std::copy(stepper_.y(), stepper_.y() + y_.size(), y_.begin());
  h = h_next;
  for (double v : y_)
    if (!std::isfinite(v)) return "slow flow: non-finite state at tau = " + fmtTau(tau_);
  return "";
}

// The first switching function that changes sign in the attempted step: sampled on the dense
// output, then bracketed to the last bits of tau by the Illinois method (sim/ode/root_find.h).
SlowFlowRun::Crossing SlowFlowRun::firstCrossing(double h) {
  Crossing first;
  if (switches_.empty()) return first;
  std::vector<double> yd(y_.size());
  for (int j = 1; j <= kSwitchSamples; ++j) {
    stepper_.interpolate(static_cast<double>(j) / kSwitchSamples, yd.data());
    rhs_.unpack(yd.data(), samples_[j]);
  }
  double theta_first = 2.0;
  for (size_t e = 0; e < switches_.size(); ++e) {
    const SlowFlowSwitch& sw = switches_[e];
    const double sigma = sw.positive ? 1.0 : -1.0;
    // beyond(tau) > 0 on the far side of the switch; <= 0 at the step's start (invariant)
    auto beyond = [&](double tau) {
      stepper_.interpolate((tau - tau_) / h, yd.data());
      rhs_.unpack(yd.data(), z_);
      return -sigma * flow_.switchValue(sw, z_.data());
    };
    double a = 0.0, fa = 0.0, b = -1.0, fb = 0.0;
    for (int j = 1; j <= kSwitchSamples; ++j) {
      const double v = -sigma * flow_.switchValue(sw, samples_[j].data());
      const double th = static_cast<double>(j) / kSwitchSamples;
      if (v > 0.0) {
        b = th;
        fb = v;
        break;
      }
      a = th;
      fa = v;
    }
    if (b < 0.0 || a >= theta_first) continue;
    const ode::Bracket br = ode::illinois(beyond, tau_ + a * h, fa, tau_ + b * h, fb);
    const double theta = (br.hi - tau_) / h;
    if (theta < theta_first) {
      theta_first = theta;
      first = {static_cast<int>(e), br.hi, theta};
    }
  }
  return first;
}

// Rows up to the switch from this step's dense output, then a restart on its far side with the
// switches flipped (every one the restart point lies beyond: simultaneous crossings).
std::string SlowFlowRun::crossSwitch(const Crossing& c, double h) {
  emitRowsUpTo(c.tau, h);
  std::vector<double> yd(y_.size());
  stepper_.interpolate(c.theta, yd.data());  // on the far side by construction
  SlowFlowSwitch& sw = switches_[c.fired];
  // a fresh step of the exact length is more accurate than the interpolant; keep it when it also
  // lands on the far side (it differs from the interpolant by ~ the local error)
  stepper_.attempt(c.theta * h);
  rhs_.unpack(stepper_.y1(), z_);
  const double sigma = sw.positive ? 1.0 : -1.0;
  if (-sigma * flow_.switchValue(sw, z_.data()) > 0.0)
    std::copy(stepper_.y1(), stepper_.y1() + y_.size(), y_.begin());
  else
    y_ = yd;
  tau_ = c.tau;
  for (double v : y_)
    if (!std::isfinite(v)) return "slow flow: non-finite state at tau = " + fmtTau(tau_);
  sw.positive = !sw.positive;
  long flips = 1;
  rhs_.unpack(y_.data(), z_);
  for (SlowFlowSwitch& other : switches_) {
    const double value = flow_.switchValue(other, z_.data());
    if ((other.positive && value < 0.0) || (!other.positive && value > 0.0)) {
      other.positive = !other.positive;
      ++flips;
    }
  }
  rhs_.modes = flow_.modesOf(switches_);
  rep_.counts.events += flips;
  const std::string storm = storm_.add(tau_, flips);
  if (!storm.empty()) return storm;
  stepper_.restart(tau_, y_.data());
  return "";
}

// The last row: the state where the run ended (tau_end when it is complete).
RunReport SlowFlowRun::finish(const std::string& failure) {
  rep_.complete = failure.empty();
  rep_.failure = failure;
  rep_.counts.rhs_evals = rhs_.evaluations;
  rhs_.unpack(y_.data(), z_);
  rep_.final_row = rows_.emit(tau_, z_);
  rep_.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0_).count();
  return rep_;
}

}  // namespace

RunReport runSlowFlow(const ScaledParams& p, const SlowFlowOptions& opt, RunSink& sink) {
  SlowFlowRun run(p, opt, sink);
  return run.run();
}

}  // namespace metrosync
