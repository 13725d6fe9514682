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

// The same bracket for a function that gives its rate too (fd(x) returns {f, f'}): Newton's
// method from the secant point, kept inside the bracket by bisection; once its step is below the
// tolerance it probes just across the root to close the bracket. Three to five evaluations on a
// smooth function (Illinois takes a dozen or more).
template <class FD>
Bracket newtonBracket(FD&& fd, double lo, double f_lo, double hi, double f_hi) {
  double x = (f_hi != f_lo) ? lo - f_lo * (hi - lo) / (f_hi - f_lo) : 0.5 * (lo + hi);
  for (int it = 0; it < 100; ++it) {
    const double tol = 4 * DBL_EPSILON * std::max(std::abs(lo), std::abs(hi)) + DBL_MIN;
    if (hi - lo <= tol) break;
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    if (!(x > lo && x < hi)) break;  // no double between the ends
    const auto [f, d] = fd(x);
    if (f >= 0) {
      hi = x;
      f_hi = f;
    } else {
      lo = x;
      f_lo = f;
    }
    double next = d != 0 ? x - f / d : 0.5 * (lo + hi);
    if (std::abs(next - x) <= 0.5 * tol)  // converged: probe across the root
      next = f >= 0 ? x - 0.5 * tol : x + 0.5 * tol;
    x = next;
  }
  return {lo, hi};
}

// The first point at or after `th` where f >= 0, found by stepping up from th in doubling steps
// of one ulp, never past `limit` (where f >= 0 is known): for a root located on an approximation
// of f a few ulps off, one evaluation of f when the approximation was right.
template <class F>
double firstPastZero(F&& f, double th, double limit) {
  double step = DBL_EPSILON * std::abs(th) + DBL_MIN;
  while (th < limit && f(th) < 0) {
    th = std::min(th + step, limit);
    step *= 2;
  }
  return th;
}

}  // namespace metrosync::ode

namespace metrosync::direct {  // the direct engine's names from before the toolkit was shared
using ode::Bracket;
using ode::illinois;
}  // namespace metrosync::direct
