// Detection of a rising witness's crossing in one accepted step of a stepper with dense output
// (sim/ode/rk_stepper.h), for the direct engine of one platform and of a network alike
// (sim/engines/direct/): a sign change between the step's ends, a hidden double crossing
// (grazing) found at the witness's extreme inside the step (the root of its rate on the dense
// output), and the first step of a slip that starts from rest (the one scan for it). The result is
// a WindowCrossing (sim/events/window.h) for locateWindow to bracket.
//
// Two kinds of witness:
//   - LinearWitness: sign * (y_a - y_b) - offset, one component or the difference of two (a tick:
//     side * theta - theta_c; a slip: -mode * (xdot - xdot_below)), with its rates from f(y);
//   - a margin: any function of the whole state (a stuck contact's |H| - bound), with its rate in
//     closed form when the engine has one.
#pragma once

#include <algorithm>
#include <optional>
#include <utility>

#include "sim/events/window.h"
#include "sim/ode/root_find.h"

namespace metrosync {

// sign * (y_a - y_b) - offset on the current step of `stepper` (b < 0: sign * y_a - offset).
template <class Stepper>
class LinearWitness {
 public:
  LinearWitness(Stepper& stepper, int a, double sign, double offset, int b = -1)
      : s_(stepper), a_(a), b_(b), sign_(sign), offset_(offset) {}
  double g0() const { return sign_ * diff(s_.y()) - offset_; }
  double g1() const { return sign_ * diff(s_.y1()) - offset_; }
  double d0() const { return sign_ * diff(s_.f()); }
  double d1() const { return sign_ * diff(s_.f1()); }
  double value(double th) const {
    return sign_ * (b_ < 0 ? s_.component(a_, th) : s_.component(a_, th) - s_.component(b_, th)) -
           offset_;
  }
  double rate(double th) const {
    return sign_ * (b_ < 0 ? s_.componentRate(a_, th)
                           : s_.componentRate(a_, th) - s_.componentRate(b_, th));
  }

 private:
  double diff(const double* y) const { return b_ < 0 ? y[a_] : y[a_] - y[b_]; }
  Stepper& s_;
  int a_, b_;
  double sign_, offset_;
};

// The first step of a slip that starts from rest (its witness exactly 0 at the step's start). The
// slip can start at a tangency of the stick margin, with an acceleration of rounding size at t0:
// the sign of the rate there says nothing, so the dip of g below zero (the slip under way) is
// looked for on the interpolant itself, and its end is the stop.
template <class W>
std::optional<WindowCrossing> detectSlipFromRest(const W& w, int index, double g1) {
  if (g1 <= 0) return std::nullopt;  // still slipping the right way (or not at all) at the end
  constexpr int kSamples = 16;
  double th_prev = 0.0;
  bool dipped = false;
  for (int s = 1; s <= kSamples; ++s) {
    const double th = static_cast<double>(s) / kSamples;
    const double v = s == kSamples ? g1 : w.value(th);
    if (v < 0) dipped = true;
    if (dipped && v >= 0) return WindowCrossing{index, {th_prev, th}};
    th_prev = th;
  }
  // no sample below zero: the whole dip (if any) lies before the first sample
  const double th1 = 1.0 / kSamples;
  double a = 0.0, b = th1;
  constexpr double kGolden = 0.6180339887498949;
  double x1 = b - kGolden * (b - a), x2 = a + kGolden * (b - a);
  double f1 = w.value(x1), f2 = w.value(x2);
  for (int it = 0; it < 60; ++it) {
    if (f1 < f2) {
      b = x2, x2 = x1, f2 = f1;
      x1 = b - kGolden * (b - a), f1 = w.value(x1);
    } else {
      a = x1, x1 = x2, f1 = f2;
      x2 = a + kGolden * (b - a), f2 = w.value(x2);
    }
  }
  const double th_min = f1 < f2 ? x1 : x2;
  if (std::min(f1, f2) < 0) return WindowCrossing{index, {th_min, th1}};
  // the slip could not get going at all (a start at a tangency that rounding put on the wrong
  // side): stop it at the first sample, where the margin has opened again
  return WindowCrossing{index, {th1, th1}, true};
}

// A linear witness's crossing in the step; allow_forced: a slip's witness, which may start from
// rest (detectSlipFromRest).
template <class W>
std::optional<WindowCrossing> detectLinear(const W& w, int index, bool allow_forced) {
  const double g0 = w.g0(), g1 = w.g1();
  auto g = [&](double th) { return w.value(th); };
  auto rate = [&](double th) { return w.rate(th); };
  if (g0 < 0) {
    if (g1 >= 0) return WindowCrossing{index, {0.0, 1.0}};
    // both ends below: a maximum inside the step may still reach zero (grazing); the rates at
    // the ends are f(y0), f(y1), inside they are the interpolant's
    const double d0 = w.d0(), d1 = w.d1();
    if (!(d0 > 0 && d1 < 0)) return std::nullopt;
    auto falling = [&](double th) { return -rate(th); };
    const ode::Bracket top = ode::illinois(falling, 0.0, -d0, 1.0, -d1);
    const double ga = g(top.lo), gb = g(top.hi);
    if (ga >= 0) return WindowCrossing{index, {0.0, top.lo}};
    if (gb >= 0) return WindowCrossing{index, {0.0, top.hi}};
    return std::nullopt;
  }
  // at or above zero at the start: a rising crossing needs a dip below zero first
  if (g0 == 0 && g1 == 0) return std::nullopt;
  if (allow_forced && g0 == 0) return detectSlipFromRest(w, index, g1);
  const double d0 = w.d0(), d1 = w.d1();
  if (d0 < 0 && d1 > 0) {
    const ode::Bracket bottom = ode::illinois(rate, 0.0, d0, 1.0, d1);
    const double ga = g(bottom.lo), gb = g(bottom.hi);
    const double th_min = ga < gb ? bottom.lo : bottom.hi;
    if (std::min(ga, gb) < 0) {
      if (g1 >= 0) return WindowCrossing{index, {th_min, 1.0}};
      return std::nullopt;  // went below and stayed there
    }
  }
  return std::nullopt;
}

// A margin (a function of the whole state, below zero while the contact holds) crossing in the
// step: g0, g1 its values at the ends; valueAt(th) on the interpolant. endRates() gives its rates
// at the ends ({d0, d1}, rateAt(th) inside) when the engine has them in closed form: a maximum
// inside the step that reaches zero is found too; without (nullopt) only a sign change.
template <class EndRates, class Value, class Rate>
std::optional<WindowCrossing> detectMargin(int index, double g0, double g1, EndRates&& endRates,
                                           Value&& valueAt, Rate&& rateAt) {
  if (g0 >= 0) return std::nullopt;  // cannot happen: a contact stays stuck only below the bound
  if (g1 >= 0) return WindowCrossing{index, {0.0, 1.0}};
  const std::optional<std::pair<double, double>> d = endRates();
  if (!d) return std::nullopt;
  const auto [d0, d1] = *d;
  if (!(d0 > 0 && d1 < 0)) return std::nullopt;
  auto falling = [&](double th) { return -rateAt(th); };
  const ode::Bracket top = ode::illinois(falling, 0.0, -d0, 1.0, -d1);
  for (double th : {top.lo, top.hi})
    if (valueAt(th) >= 0) return WindowCrossing{index, {0.0, th}};
  return std::nullopt;
}

}  // namespace metrosync
