// The localization window, for every engine that steps with dense output (the direct engine's
// ticks and platform switches, the slow flow's switching surfaces): after an accepted step,
// each witness that crossed (in its declared direction, sim/events/witness.h) is bracketed on the
// step's interpolant; the window ends at the earliest bracket's far end, and every witness whose
// value there is past zero belongs to the window, however close its crossing is to the first
// one (0, 1e-16, 1e-10 apart): the engine then acts on all of them at once and restarts. Nothing
// is disarmed by time.
//
// Positions are fractions th of the step, in [0, 1].
#pragma once

#include <algorithm>
#include <optional>
#include <vector>

#include "sim/events/witness.h"
#include "sim/ode/root_find.h"

namespace metrosync {

// A crossing found in the current step: the bracket of its root in th.
struct WindowCrossing {
  int witness = 0;
  ode::Bracket th;
  bool forced = false;  // the engine fixed the position itself: not to be bracketed further
};

// The first sign change of a rising witness on `samples` equally spaced points th = s / samples,
// s = 1..samples (sample(s) gives its value there), from g0 at th = 0: the bracket between the
// last sample not past zero and the first one past it. A witness that crosses zero twice between
// two samples is not seen: the engines choose `samples` from how far a step may move the state.
template <class Sample>
std::optional<ode::Bracket> scanRising(Sample&& sample, double g0, int samples) {
  double th_prev = 0.0, g_prev = g0;
  for (int s = 1; s <= samples; ++s) {
    const double th = static_cast<double>(s) / samples, g = sample(s);
    if (crossed(Direction::Rising, g_prev, g)) return ode::Bracket{th_prev, th};
    th_prev = th;
    g_prev = g;
  }
  return std::nullopt;
}

// Brackets the crossings to a few ulps, earliest first (sorted in place), and returns the window's
// end: the earliest upper end. value(witness, th) is the rising witness on the interpolant. A
// crossing that starts after the window's end cannot be the first and is not bracketed.
template <class Value>
double locateWindow(std::vector<WindowCrossing>& found, Value&& value) {
  std::sort(found.begin(), found.end(),
            [](const WindowCrossing& a, const WindowCrossing& b) { return a.th.lo < b.th.lo; });
  double th_e = 2.0;
  for (WindowCrossing& c : found) {
    if (c.th.lo >= th_e) break;
    if (!c.forced && c.th.hi > c.th.lo) {
      auto g = [&](double th) { return value(c.witness, th); };
      // still below zero at the window's end found so far: a bracket holds one sign change (the
      // engines' detection assumes it), so this root lies after th_e and cannot move it; skip
      // the bracketing (tens of interpolations; with N metronomes most steps end at an event)
      if (th_e < c.th.hi && g(th_e) < 0) continue;
      c.th = ode::illinois(g, c.th.lo, g(c.th.lo), c.th.hi, g(c.th.hi));
    }
    th_e = std::min(th_e, c.th.hi);
  }
  return th_e;
}

// The same, for witnesses that have a cheap approximation on the step (approx(witness) returns
// an optional callable th -> value with valueRate(th) -> {value, rate}, e.g. one component's
// interpolant as a polynomial in th, a few ulps from the exact value): the root is bracketed on the
// approximation, and its upper end moved up by ulps until the exact witness is past zero there. The
// window still ends where the exact witness has crossed -- all that the resolver needs -- for one
// or two exact evaluations instead of dozens (the first of them is the window end's own
// interpolation weights, reused).
template <class Value, class Approx>
double locateWindow(std::vector<WindowCrossing>& found, Value&& value, Approx&& approx) {
  std::sort(found.begin(), found.end(),
            [](const WindowCrossing& a, const WindowCrossing& b) { return a.th.lo < b.th.lo; });
  double th_e = 2.0;
  for (WindowCrossing& c : found) {
    if (c.th.lo >= th_e) break;
    if (!c.forced && c.th.hi > c.th.lo) {
      auto g = [&](double th) { return value(c.witness, th); };
      if (th_e < c.th.hi && g(th_e) < 0) continue;  // see locateWindow above
      const auto a = approx(c.witness);
      const double a_lo = a ? (*a)(c.th.lo) : 0.0, a_hi = a ? (*a)(c.th.hi) : 0.0;
      if (a && a_lo < 0 && a_hi >= 0) {  // the approximation brackets the root too
        auto value_rate = [&](double th) { return a->valueRate(th); };
        const ode::Bracket coarse = ode::newtonBracket(value_rate, c.th.lo, a_lo, c.th.hi, a_hi);
        c.th = {coarse.lo, ode::firstPastZero(g, coarse.hi, c.th.hi)};
      } else {
        c.th = ode::illinois(g, c.th.lo, g(c.th.lo), c.th.hi, g(c.th.hi));
      }
    }
    th_e = std::min(th_e, c.th.hi);
  }
  return th_e;
}

}  // namespace metrosync
