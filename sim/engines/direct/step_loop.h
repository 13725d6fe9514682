// The direct engine's run loop, one for a single rig and for a network of platforms (issue 24):
// steps to t_end; each kept step either has no crossing (samples, re-arming, advance) or ends at
// its earliest event window (sim/events/window.h), resolved before the next step. The run says
// what a step, a crossing, a sample and a window are for its model:
//
//   auto& stepper();                                  the embedded RK pair (sim/ode/rk_stepper.h)
//   const double* mechanicalEnd(const double* y);     the end of y's mechanical part (no ledger)
//   bool complete() const;  void fail(double t, const std::string& why);
//   void countStep();                                 one kept step
//   bool findCrossings();                             true: a witness crossed in the kept step
//   void emitSamplesBefore(double t, bool inclusive); the samples due before t (or at it)
//   void rearm(const double* y);                      escapements re-armed on the step's end y
//   double locateWindow();                            the window's end, a fraction of the step
//   void resolveWindow(double t_e, double th_e);      the window resolved, the stepper restarted
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "sim/events/storm_guard.h"

namespace metrosync::direct {

// The step to try first: half a fast period shortened to the accuracy's share of the method's
// order (the error per step of an order-p method goes as h^(p+1)).
inline double firstStepSize(double h_max, double period, double accuracy, int order) {
  return std::min(h_max, 0.5 * period * std::pow(accuracy, 1.0 / (order + 1)));
}

// A step that produced a NaN or an infinity is redone 4 times smaller, at most this many times
// in a row (a state that is not finite itself fails at once).
constexpr int kMaxNonfiniteRetries = 50;

// One attempt; false when rejected, with h set to the retry's size (and the run failed when the
// state cannot be made finite); err: the step's error estimate.
template <class Run>
bool attemptStep(Run& run, double step, double& h, double& err, int& nonfinite) {
  auto& stepper = run.stepper();
  err = stepper.attempt(step);
  if (err <= 1.0) {
    nonfinite = 0;
    return true;
  }
  if (!std::isfinite(err) && (++nonfinite > kMaxNonfiniteRetries ||
                              !std::all_of(stepper.y(), run.mechanicalEnd(stepper.y()),
                                           [](double v) { return std::isfinite(v); }))) {
    run.fail(stepper.t(), "non-finite state");
    return false;
  }
  h = std::isfinite(err) ? stepper.nextStepSize(step, err, false) : 0.25 * step;
  return false;
}

// The shortest step at time t before the step size counts as underflowed: a few ulps of t, and
// never below 1e-14 of a fast period.
inline double minStepSize(double t, double period) {
  return std::max(1e-14 * period, 16 * std::numeric_limits<double>::epsilon() * t);
}

template <class Run>
void integrateTo(Run& run, double t_end, double h_first, double h_max, double period,
                 StormGuard& storm) {
  auto& stepper = run.stepper();
  double h = h_first;
  int nonfinite = 0;  // consecutive attempts that produced a NaN or an infinity
  while (stepper.t() < t_end) {
    const double t0 = stepper.t();
    const bool last = t0 + h >= t_end * (1 - 4 * std::numeric_limits<double>::epsilon());
    const double step = last ? t_end - t0 : h;
    if (!(step > minStepSize(t0, period)) && !last) {
      run.fail(t0, "step size underflow (h = " + std::to_string(step) + " s)");
      break;
    }
    double err = 0.0;
    if (!attemptStep(run, step, h, err, nonfinite)) {
      if (!run.complete()) break;
      continue;
    }

    run.countStep();
    const double t1 = last ? t_end : stepper.t1();
    h = std::min(h_max, stepper.nextStepSize(step, err, true));
    if (!run.findCrossings()) {
      run.emitSamplesBefore(t1, true);
      run.rearm(stepper.y1());
      stepper.advance();
      if (last) break;
      continue;
    }
    const double th_e = run.locateWindow();
    const double t_e = th_e >= 1.0 ? t1 : t0 + th_e * step;
    run.emitSamplesBefore(t_e, false);
    run.resolveWindow(t_e, th_e);
    if (storm.note(t_e)) {
      run.fail(t_e, storm.why());
      break;
    }
    if (last && th_e >= 1.0) break;
  }
}

}  // namespace metrosync::direct
