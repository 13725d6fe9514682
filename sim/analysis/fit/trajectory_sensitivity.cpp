#include "sim/analysis/fit/trajectory_sensitivity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sim/analysis/periodic_orbit/saltation.h"
#include "sim/ode/rk_stepper.h"

namespace metrosync {

namespace {

using orbit::Mat;
using orbit::PhysicalModel;
using orbit::Vec;

// A step below this fraction of the longest step is an underflow (a state the model cannot
// continue): the pieces are smooth and the engine has crossed them.
constexpr double kMinStepFraction = 1e-12;

// The state and Y = dy/dq (column-major after it): y' = f(y), Y' = J Y + df/dp dirs.
struct Extended : ode::OdeRhs {
  Extended(const PhysicalModel& m, const Mat& dirs)
      : model(m), dirs(dirs), d(m.dim()), k(static_cast<int>(dirs.cols())), f(d + 2) {}
  void eval(const double* y, double* dy) override {
    model.equations().rhs(y, mode, f.data());  // (+ the engine's two quadratures, not kept)
    std::copy(f.begin(), f.begin() + d, dy);
    model.variationalRates(y, mode, y + d, dirs.data(), k, dy + d);
  }
  const PhysicalModel& model;
  const Mat& dirs;
  int d, k;
  std::vector<double> f;
  PlatformMode mode = PlatformMode::Stuck;
};

// Walks the run piece by piece, writing the requested rows as the steps pass them.
class Walk {
 public:
  Walk(const PhysicalModel& m, const Mat& dirs, const std::vector<double>& times,
       const std::vector<int>& component, const SensitivitySettings& s)
      : m_(m),
        dirs_(dirs),
        times_(times),
        component_(component),
        s_(s),
        d_(m.dim()),
        k_(static_cast<int>(dirs.cols())),
        rhs_(m, dirs),
        stepper_(ode::rkTableau("verner76"), d_ + d_ * k_, rhs_),
        out_(Mat::Zero(static_cast<int>(times.size()), k_)),
        x_(d_ + d_ * k_) {
    std::vector<double> atol(d_ + d_ * k_, -1.0);  // Y: not controlled
    std::copy(s.atol.begin(), s.atol.begin() + d_, atol.begin());
    stepper_.setTolerances(s.accuracy, atol);
  }

  // y and Y at the start (the engine's settled mode): Y = dy0/dq, a held platform's xdot
  // perturbation stopped by friction at once
  void start(PlatformMode mode) {
    const Vec y0 = m_.startState();
    Mat Y = dirs_.bottomRows(d_);
    if (m_.coulomb() && mode == PlatformMode::Stuck)
      Y = m_.plasticStopJacobian(y0) * Y + m_.plasticStopParameterJacobian(y0) * dirs_;
    set(0.0, y0, Y, mode);
  }
  // Integrates to t1, writing every requested row with a time in [t, t1) (and t1 itself when
  // `last`).
  void to(double t1, bool last);
  // The window's jump: y becomes the engine's after-state, Y = S Y + Sp dirs.
  void jump(const orbit::EngineWindow& w) {
    const orbit::WindowJump j = orbit::windowJump(m_, w, true);
    const Eigen::Map<const Mat> Y(x_.data() + d_, d_, k_);
    set(w.t, w.after, j.S * Y + j.Sp * dirs_, w.mode_after);
  }
  // The rows left at times up to now, from the state between pieces.
  void writeHere() {
    for (; next_ < times_.size() && times_[next_] <= t_; ++next_)
      for (int q = 0; q < k_ && component_[next_] >= 0; ++q)
        out_(static_cast<int>(next_), q) = x_[d_ + q * d_ + component_[next_]];
  }
  Mat result() { return std::move(out_); }

 private:
  void set(double t, const Vec& y, const Mat& Y, PlatformMode mode) {
    t_ = t;
    std::copy(y.data(), y.data() + d_, x_.begin());
    std::copy(Y.data(), Y.data() + d_ * k_, x_.begin() + d_);
    rhs_.mode = mode;
  }
  void writeRows(double t_hi, bool inclusive);

  const PhysicalModel& m_;
  const Mat& dirs_;
  const std::vector<double>& times_;
  const std::vector<int>& component_;
  const SensitivitySettings& s_;
  int d_, k_;
  Extended rhs_;
  ode::RkStepper stepper_;
  Mat out_;
  std::vector<double> x_;  // the extended state at t_ between pieces
  double t_ = 0.0, h_ = 0.0;
  std::size_t next_ = 0;  // the next requested row
};

// Cubic Hermite on the step just attempted: Y's values and rates (the variational equations') at
// both ends.
void Walk::writeRows(double t_hi, bool inclusive) {
  const double t0 = stepper_.t(), h = stepper_.h();
  const double *y0 = stepper_.y(), *f0 = stepper_.f(), *y1 = stepper_.y1(), *f1 = stepper_.f1();
  for (; next_ < times_.size() && (times_[next_] < t_hi || (inclusive && times_[next_] == t_hi));
       ++next_) {
    const int c = component_[next_];
    if (c < 0) continue;
    const double u = std::clamp((times_[next_] - t0) / h, 0.0, 1.0), u2 = u * u, u3 = u2 * u;
    const double a0 = 2 * u3 - 3 * u2 + 1, b0 = (u3 - 2 * u2 + u) * h, a1 = -2 * u3 + 3 * u2,
                 b1 = (u3 - u2) * h;
    for (int q = 0; q < k_; ++q) {
      const int e = d_ + q * d_ + c;
      out_(static_cast<int>(next_), q) = a0 * y0[e] + b0 * f0[e] + a1 * y1[e] + b1 * f1[e];
    }
  }
}

void Walk::to(double t1, bool last) {
  if (!(t1 > t_)) return;
  stepper_.restart(t_, x_.data());
  if (h_ == 0.0) h_ = stepper_.initialStepSize(std::min(s_.max_step_s, t1 - t_));
  const double min_step = kMinStepFraction * s_.max_step_s;
  while (stepper_.t() < t1) {
    const double t0 = stepper_.t();
    const bool final_step = t0 + h_ >= t1 * (1 - 4 * std::numeric_limits<double>::epsilon());
    const double step = final_step ? t1 - t0 : h_;
    const double err = stepper_.attempt(step);
    if (!(err <= 1.0)) {
      if (!(step > min_step)) throw std::runtime_error("sensitivities: step size underflow");
      h_ = std::isfinite(err) ? stepper_.nextStepSize(step, err, false) : 0.25 * step;
      continue;
    }
    writeRows(final_step ? t1 : stepper_.t1(), final_step && last);
    const double next = std::min(s_.max_step_s, stepper_.nextStepSize(step, err, true));
    if (!final_step || next < h_) h_ = next;  // a step cut short by t1 is no measure of h
    stepper_.advance();
    if (final_step) break;
  }
  t_ = t1;
  std::copy(stepper_.y(), stepper_.y() + x_.size(), x_.begin());
}

}  // namespace

Mat trajectorySensitivities(const PhysicalModel& model, const orbit::EngineTrace& trace,
                            const Mat& dirs, const std::vector<double>& times,
                            const std::vector<int>& component,
                            const SensitivitySettings& settings) {
  Walk walk(model, dirs, times, component, settings);
  walk.start(trace.start_mode);
  const double t_end = times.empty() ? 0.0 : times.back();
  for (const orbit::EngineWindow& w : trace.windows) {
    if (w.t > t_end) break;
    walk.to(w.t, false);
    walk.jump(w);
  }
  walk.to(t_end, true);
  walk.writeHere();  // rows at a time no step reached (the start, a window's time at the end)
  return walk.result();
}

}  // namespace metrosync
