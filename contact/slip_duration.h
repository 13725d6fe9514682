// The stick-slip duration of the Coulomb platform (appendix "ac", eq. d1) and the elementary
// functions around it, shared by the averaged response and the periodic solution
// (contact/averaged_response.h).
//
// With q = sqrt(s^2 - 1) = B cos t0, the slip that starts at t0 = arcsin(1/s) lasts u = t1 - t0,
// the root in (0, 2 pi) of
//   g(u) = (u - sin u) / (1 - cos u) = q
// (the paper's cos t1 - cos t0 + (t1 - t0)/s = 0 without its trivial root t1 = t0). g is odd,
// convex and increasing on (0, 2 pi), g ~ u/3, g(pi) = pi/2 (the stick-slip range q <= pi/2 is
// u <= pi, i.e. t1 in (pi - t0, t0 + pi]), and g -> inf at 2 pi (the continuation q > pi/2).
#pragma once

namespace metrosync {

// 1 - cos u, u - sin u and u^2/2 - (1 - cos u), without cancellation at small u.
double oneMinusCos(double u);
double uMinusSin(double u);
double halfSquareMinusOneMinusCos(double u);

// g(u) = (u - sin u) / (1 - cos u).
double coulombSlipFunction(double u);

// u(q), the root of g(u) = q in [0, 2 pi): 0 for q <= 0 or NaN, NaN for q = +inf. The slow flow
// evaluates this at every right-hand side in the stick-slip regime, so for q <= pi/2 it starts
// from a piecewise Chebyshev interpolant of u(q)/q in q^2 (relative error ~2e-15) and takes one
// Newton step, which squares that error (g is smooth and g' >= 1/3 on the range): the result
// agrees with the converged iteration to a few ulp (tests/contact/test_slip_duration.cpp). Beyond
// pi/2 (the analytic continuation) it runs the reference iteration.
double coulombSlipDuration(double q);

// The reference: bisection beyond pi/2, then Newton from the right of the root (monotone, since
// g is convex increasing) until the step is below 2e-16 u. ~4-8 iterations of three sines.
double coulombSlipDurationReference(double q);

}  // namespace metrosync
