// Root bracketing on [lo, hi] for a function with f(lo) < 0 <= f(hi): the Illinois variant of
// regula falsi (superlinear on smooth functions), with bisection whenever it stalls. Ends with a
// bracket no wider than a few units in the last place of its ends, so that the event is placed
// just past the root: f(hi) >= 0, and a witness evaluated there has crossed.
#pragma once

#include <cfloat>
#include <cmath>

namespace metrosync::ode {

struct Bracket {
  double lo = 0.0, hi = 0.0;
};

template <class F>
Bracket illinois(F&& f, double lo, double f_lo, double hi, double f_hi) {
  int retained = 0;  // +1: hi moved twice running; -1: lo moved twice running
  double width = hi - lo;
  for (int it = 0; it < 200; ++it) {
    const double tol = 4 * DBL_EPSILON * std::max(std::abs(lo), std::abs(hi)) + DBL_MIN;
    if (hi - lo <= tol) break;
    double x = (f_hi != f_lo) ? lo - f_lo * (hi - lo) / (f_hi - f_lo) : 0.5 * (lo + hi);
    // bisect when the secant leaves the bracket or the bracket has not halved in two steps
    if (!(x > lo && x < hi) || (it % 2 == 1 && hi - lo > 0.5 * width)) x = 0.5 * (lo + hi);
    if (it % 2 == 1) width = hi - lo;
    if (!(x > lo && x < hi)) break;  // no double between the ends
    const double fx = f(x);
    if (fx >= 0) {
      hi = x;
      f_hi = fx;
      if (retained == 1) f_lo *= 0.5;
      retained = 1;
    } else {
      lo = x;
      f_lo = fx;
      if (retained == -1) f_hi *= 0.5;
      retained = -1;
    }
  }
  return {lo, hi};
}

}  // namespace metrosync::ode

namespace metrosync::direct {  // the direct engine's names from before the toolkit was shared
using ode::Bracket;
using ode::illinois;
}  // namespace metrosync::direct
