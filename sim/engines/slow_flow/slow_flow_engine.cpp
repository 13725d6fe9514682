// The slow flow's integration loop: models/slow_flow.h says what the equations, modes and switching
// functions are; this file steps them with the shared ODE toolkit (sim/ode: the dopri5 tableau,
// its step-size control, dense output and Illinois root finding), holds the modes fixed over a
// step, locates the first switch crossed on the dense output, restarts there, and writes rows.
#include "sim/engines/slow_flow/slow_flow_engine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>

#include "base/constants.h"
#include "base/number_text.h"
#include "sim/events/storm_guard.h"
#include "sim/events/window.h"
#include "sim/ode/rk_stepper.h"
#include "sim/record/split_timer.h"

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

// The flow in a co-rotating frame, in the stepper's real coordinates. The slow flow is equivariant
// under a common rotation z -> z e^{i theta} (the betas depend on |Z| only), so w = z e^{-i theta}
// with theta' = Omega(w) obeys
//   dw/dtau = f(w) - i Omega(w) w,   Omega(w) = sum Im(conj(w_a) f_a(w)) / sum |w_a|^2,
// the amplitude-weighted mean phase velocity: the frame turns with the metronomes, so that a
// phase-locked state (a relative equilibrium of the flow, turning at a constant rate) is an
// equilibrium of w and the step size is no longer limited by the common rotation (~A^2/16 rad per
// unit tau, which made the steps ~0.1 long at rtol 1e-8). A_i = |w_i|, the phase differences and
// the switching functions are rotation invariant; theta is carried as the last, uncontrolled
// component (atol < 0: a quadrature nothing depends on) so that z = w e^{i theta} is available for
// the rows. y = (Re w_a, Im w_a) over the unlocked a, then theta.
struct FlowRhs : ode::OdeRhs {
  explicit FlowRhs(const SlowFlow& flow) : f(flow), zs(flow.size()), dzs(flow.size()) {}

  int frameIndex() const { return 2 * static_cast<int>(f.active().size()); }
  // w (the co-rotating amplitudes) from y
  void unpack(const double* y, std::vector<cplx>& z) const {
    z.assign(f.size(), 0.0);
    const auto& act = f.active();
    for (size_t m = 0; m < act.size(); ++m) z[act[m]] = cplx(y[2 * m], y[2 * m + 1]);
  }
  // z = w e^{i theta} (the amplitudes in the fixed frame) from y
  void unpackFixed(const double* y, std::vector<cplx>& z) const {
    unpack(y, z);
    const cplx rot = std::polar(1.0, y[frameIndex()]);
    for (int i : f.active()) z[i] *= rot;
  }
  void eval(const double* y, double* dy) override {
    ++evaluations;
    unpack(y, zs);
    f.rhs(modes, zs.data(), dzs.data());
    const auto& act = f.active();
    double num = 0.0, den = 0.0;
    for (int i : act) {
      num += zs[i].real() * dzs[i].imag() - zs[i].imag() * dzs[i].real();  // Im(conj(w) f)
      den += std::norm(zs[i]);
    }
    const double omega = den > 0.0 ? num / den : 0.0;
    for (size_t m = 0; m < act.size(); ++m) {
      const cplx w = zs[act[m]], d = dzs[act[m]];
      dy[2 * m] = d.real() + omega * w.imag();  // f - i Omega w
      dy[2 * m + 1] = d.imag() - omega * w.real();
    }
    dy[frameIndex()] = omega;
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

class SlowFlowRun {
 public:
  SlowFlowRun(const ScaledParams& p, const SlowFlowOptions& opt, RunSink& sink);
  RunReport run();

 private:
  std::string step(double& h);                 // one attempted step; a failure message, or empty
  double switchAt(int e, double th);           // switch e's witness on the dense output
  std::optional<double> findWindow(double h);  // the window's end (fraction of the step)
  std::string crossSwitches(double th_e, double h);
  void emitRowsUpTo(double tau_hi, double h);
  RunReport finish(const std::string& failure);

  const ScaledParams& p_;
  const SlowFlowOptions& opt_;
  SplitTimer timer_;  // the engine's time against the recording's
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
  std::vector<double> scratch_;  // (y_.size()): dense-output samples, no allocation per step
  std::vector<cplx> z_;
  std::vector<std::vector<cplx>> samples_;  // the dense output at th = j / kSwitchSamples
  std::vector<WindowCrossing> found_;
};

SlowFlowRun::SlowFlowRun(const ScaledParams& p, const SlowFlowOptions& opt, RunSink& sink)
    : p_(p),
      opt_(opt),
      flow_(p),
      rhs_(flow_),
      stepper_(ode::rkTableau("dopri5"), rhs_.frameIndex() + 1, rhs_),
      rows_(flow_, p, sink),
      storm_(kTwoPi * p.epsilon, opt.storm_events, opt.storm_window),  // a fast period in tau
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
  y_.push_back(0.0);  // the frame's angle theta: w = z at tau = 0
  scratch_.resize(y_.size());
  switches_ = flow_.switches(z_.data());
  rhs_.modes = flow_.modesOf(switches_);
  std::vector<double> atol(y_.size(), opt.atol);
  atol.back() = -1.0;  // theta is not error-controlled
  stepper_.setTolerances(opt.rtol, atol);
  stepper_.setNorm(ode::RkStepper::Norm::Rms);  // as DOPRI5 and the slow flow always did
}

// Grid rows tau_k <= min(tau_hi, tau_end), from the attempted step's dense output when h > 0.
void SlowFlowRun::emitRowsUpTo(double tau_hi, double h) {
  std::vector<double>& yr = scratch_;
  for (;;) {
    const double tk = envelopeTau(p_.epsilon, next_row_);
    if (tk > tau_hi || tk > opt_.tau_end) break;
    RecordingScope rec(timer_);
    if (h > 0.0)
      stepper_.interpolate(std::clamp((tk - tau_) / h, 0.0, 1.0), yr.data());
    else
      yr = y_;
    rhs_.unpackFixed(yr.data(), z_);
    rows_.emit(tk, z_);
    ++next_row_;
  }
}

RunReport SlowFlowRun::run() {
  rows_.emit(0.0, z_);           // the start's envelope
  if (flow_.active().empty()) {  // every metronome locked: nothing moves
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
           " steps, stopped at tau = " + numberText(tau_, 9);
  const bool to_end = h >= opt_.tau_end - tau_;
  if (to_end) h = opt_.tau_end - tau_;
  const double err = stepper_.attempt(h);
  if (!(err <= 1.0)) {  // rejected (a NaN included)
    h = std::isfinite(err) ? stepper_.nextStepSize(h, err, false) : h / kNonFiniteShrink;
    last_rejected_ = true;
    if (h < kMinStepRelative * std::max(1.0, std::fabs(tau_)))
      return "slow flow: step size underflow at tau = " + numberText(tau_, 9);
    return "";
  }
  double h_next = stepper_.nextStepSize(h, err, true);
  if (last_rejected_) h_next = std::min(h_next, h);  // no growth right after a rejection
  last_rejected_ = false;
  ++rep_.counts.steps;
  if (const std::optional<double> th_e = findWindow(h)) {
    const std::string failure = crossSwitches(*th_e, h);
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
    if (!std::isfinite(v)) return "slow flow: non-finite state at tau = " + numberText(tau_, 9);
  return "";
}

double SlowFlowRun::switchAt(int e, double th) {
  stepper_.interpolate(th, scratch_.data());
  rhs_.unpack(scratch_.data(), z_);
  return SlowFlowSwitchWitness::value(flow_, switches_[e], z_.data());
}

// The switches crossed in the attempted step (each witness sampled on the dense output, then
// bracketed to the last bits by the shared window locator, sim/events/window.h); the window's
// end, or nothing when none crossed.
std::optional<double> SlowFlowRun::findWindow(double h) {
  found_.clear();
  if (switches_.empty()) return std::nullopt;
  for (int j = 1; j <= kSwitchSamples; ++j) {
    stepper_.interpolate(static_cast<double>(j) / kSwitchSamples, scratch_.data());
    rhs_.unpack(scratch_.data(), samples_[j]);
  }
  rhs_.unpack(y_.data(), z_);
  for (int e = 0; e < static_cast<int>(switches_.size()); ++e) {
    auto sample = [&](int j) {
      return SlowFlowSwitchWitness::value(flow_, switches_[e], samples_[j].data());
    };
    const double g0 = SlowFlowSwitchWitness::value(flow_, switches_[e], z_.data());
    if (auto br = scanRising(sample, g0, kSwitchSamples)) found_.push_back({e, *br});
  }
  if (found_.empty()) return std::nullopt;
  return locateWindow(found_, [&](int e, double th) { return switchAt(e, th); });
}

// Rows up to the window from this step's dense output, then a restart at its end with every
// switch flipped whose witness is past zero there (all the crossings of the window at once).
std::string SlowFlowRun::crossSwitches(double th_e, double h) {
  const double tau_e = tau_ + th_e * h;
  emitRowsUpTo(tau_e, h);
  std::vector<double> yd(y_.size());
  stepper_.interpolate(th_e, yd.data());  // the first switch is past zero here by construction
  const int first = found_.front().witness;
  // a fresh step of the exact length is more accurate than the interpolant; keep it when it also
  // lands past the first switch (it differs from the interpolant by ~ the local error)
  stepper_.attempt(th_e * h);
  rhs_.unpack(stepper_.y1(), z_);
  if (SlowFlowSwitchWitness::value(flow_, switches_[first], z_.data()) >= 0.0)
    std::copy(stepper_.y1(), stepper_.y1() + y_.size(), y_.begin());
  else
    y_ = yd;
  tau_ = tau_e;
  for (double v : y_)
    if (!std::isfinite(v)) return "slow flow: non-finite state at tau = " + numberText(tau_, 9);
  rhs_.unpack(y_.data(), z_);
  long flips = 0;
  for (int e = 0; e < static_cast<int>(switches_.size()); ++e) {
    const double g = SlowFlowSwitchWitness::value(flow_, switches_[e], z_.data());
    if (g > 0.0 || (e == first && g >= 0.0)) {
      switches_[e].positive = !switches_[e].positive;
      ++flips;
    }
  }
  rhs_.modes = flow_.modesOf(switches_);
  rep_.counts.events += flips;
  for (long k = 0; k < flips; ++k)
    if (storm_.note(tau_))
      return "slow flow: " + storm_.why() + ", at tau = " + numberText(tau_, 9);
  stepper_.restart(tau_, y_.data());
  return "";
}

// The last row: the state where the run ended (tau_end when it is complete).
RunReport SlowFlowRun::finish(const std::string& failure) {
  rep_.complete = failure.empty();
  rep_.failure = failure;
  rep_.counts.rhs_evals = rhs_.evaluations;
  rhs_.unpackFixed(y_.data(), z_);
  rep_.final_row = rows_.emit(tau_, z_);
  rep_.wall_seconds = timer_.wallSeconds();
  rep_.engine_seconds = rep_.wall_seconds - timer_.recordingSeconds(rep_.wall_seconds);
  return rep_;
}

}  // namespace

RunReport runSlowFlow(const ScaledParams& p, const SlowFlowOptions& opt, RunSink& sink) {
  SlowFlowRun run(p, opt, sink);
  return run.run();
}

}  // namespace metrosync
