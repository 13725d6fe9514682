// The averaged Coulomb response (contact/averaged_response.h) against an evaluation that shares
// nothing with the closed forms: the driven Coulomb element y'' = B sin t - F (unit friction,
// eq. c1) time-stepped from rest with classical RK4, the stick and slip instants located by
// bisection on the stepped solution, and the projections of y'' on sin t and cos t accumulated
// as quadratures of the same steps. The stick-slip times t0, t1 (the root of the t1 equation in
// (pi - t0, t0 + pi], not its trivial root t1 = t0) and beta1, beta2 are compared at many s.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "base/constants.h"
#include "contact/averaged_response.h"

namespace metrosync {
namespace {

const double kSb = std::sqrt(1.0 + kPi * kPi / 4.0);

// The element's state: slip velocity v, the mode (0 stuck, +-1 slipping forwards / backwards)
// and the two projections of y'' (sin, cos) accumulated since the last reset.
struct Element {
  double B = 0.0;
  double t = 0.0, v = 0.0;
  int mode = 0;
  double ps = 0.0, pc = 0.0;
  std::vector<double> slips, sticks;  // instants where a slip starts / the element sticks

  double acc(double t_, int m) const { return m == 0 ? 0.0 : B * std::sin(t_) - m; }
  // one RK4 step of (v, ps, pc) from (t, v) over h in mode m (the state is not changed)
  void rk4(double h, int m, double& v1, double& ps1, double& pc1) const {
    auto f = [&](double tt) { return acc(tt, m); };
    const double a0 = f(t), a1 = f(t + 0.5 * h), a2 = f(t + h);
    // v' = a(t) does not depend on v: RK4 is Simpson's rule, as are the projections
    v1 = v + h / 6.0 * (a0 + 4.0 * a1 + a2);
    ps1 =
        ps + h / 6.0 * (a0 * std::sin(t) + 4.0 * a1 * std::sin(t + 0.5 * h) + a2 * std::sin(t + h));
    pc1 =
        pc + h / 6.0 * (a0 * std::cos(t) + 4.0 * a1 * std::cos(t + 0.5 * h) + a2 * std::cos(t + h));
  }
  void advance(double h) {
    double v1, ps1, pc1;
    rk4(h, mode, v1, ps1, pc1);
    t += h;
    v = v1;
    ps = ps1;
    pc = pc1;
  }
  // the step's fraction in (0, 1] where event(fraction) first holds (it holds at 1), by bisection
  template <class Event>
  double locate(double h, Event&& event) const {
    double a = 0.0, b = 1.0;
    for (int it = 0; it < 60; ++it) {
      const double m = 0.5 * (a + b);
      (event(m * h) ? b : a) = m;
    }
    return b;
  }
  // A step of h; an event inside it (slip start, stick, reversal) ends the step there.
  void step(double h) {
    if (mode == 0) {
      auto slips_now = [&](double dt) { return std::fabs(B * std::sin(t + dt)) > 1.0; };
      if (!slips_now(h)) return advance(h);
      advance(locate(h, slips_now) * h);
      mode = B * std::sin(t) > 0.0 ? 1 : -1;
      slips.push_back(t);
      return;
    }
    double v1, ps1, pc1;
    rk4(h, mode, v1, ps1, pc1);
    if (mode * v1 > 0.0) return advance(h);
    auto stopped = [&](double dt) {
      double vv, a, b;
      rk4(dt, mode, vv, a, b);
      return mode * vv <= 0.0;
    };
    advance(locate(h, stopped) * h);
    v = 0.0;
    // friction holds the element when the drive is within the friction limit; else it reverses
    if (std::fabs(B * std::sin(t)) <= 1.0) {
      mode = 0;
      sticks.push_back(t);
    } else {
      mode = -mode;
    }
  }
};

struct Stepped {
  AveragedResponse beta;
  double t0 = NAN, t1 = NAN;  // first slip and stick of the last period, reduced to [0, 2 pi)
};

// Runs the element from rest for `periods` drive periods at `per_period` steps each and projects
// over the last one (the periodic state: stick-slip forgets its start at the first stick; in pure
// slip the mean velocity left from the start decays over tens of periods, the more slowly the
// larger s).
Stepped stepElement(double B, int periods, int per_period) {
  Element e;
  e.B = B;
  const double dt = 2.0 * kPi / per_period;
  for (int p = 0; p < periods; ++p) {
    if (p == periods - 1) {
      e.ps = e.pc = 0.0;
      e.slips.clear();
      e.sticks.clear();
    }
    const double end = 2.0 * kPi * (p + 1);
    while (e.t < end - 1e-13) e.step(std::fmin(dt, end - e.t));
  }
  Stepped s;
  s.beta = {e.ps / (2.0 * kPi * B), e.pc / (2.0 * kPi * B)};
  const double base = 2.0 * kPi * (periods - 1);
  if (!e.slips.empty()) {
    s.t0 = e.slips.front() - base;
    for (double t : e.sticks)  // the stick that ends the slip starting at t0
      if (t > e.slips.front()) {
        s.t1 = t - base;
        break;
      }
  }
  return s;
}

TEST(CoulombByTimeStepping, BetasMatchTheClosedFormsAtManyDriveStrengths) {
  // Simpson's rule on smooth pieces at 2000 steps per period: error ~ (pi/1000)^4 / 180 ~ 1e-12
  // per unit; the events are located to 1e-16 of a step (measured: at most 2.2e-12 over this
  // grid). 1e-10 leaves a 50x margin and is 100x tighter than the slow flow's local error target
  // at the default accuracy (1e-8).
  std::vector<double> ss;
  for (int k = 0; k <= 60; ++k) ss.push_back(0.8 + 0.05 * k);  // 0.8 .. 3.8: all three regimes
  for (double d : {1e-3, 1e-2}) {
    ss.push_back(1.0 + d);
    ss.push_back(kSb - d);
    ss.push_back(kSb + d);
  }
  for (double s : ss) {
    const Stepped st = stepElement(s, s > kSb ? 80 : 4, 2000);
    const AveragedResponse b = coulombResponse(s);
    EXPECT_NEAR(b.beta1, st.beta.beta1, 1e-10) << "s = " << s;
    EXPECT_NEAR(b.beta2, st.beta.beta2, 1e-10) << "s = " << s;
  }
}

TEST(CoulombByTimeStepping, StickSlipTimesMatchTheT1Root) {
  // t0 = arcsin(1/s), t1 = t0 + u: the stepped element's first slip and first stick of a period.
  // The instants are located to rounding; the velocity that decides the stick is accurate to
  // ~1e-12, and |v'| at the stick is |B sin t1 - 1| >= ~1e-2 here: ~1e-10 on t1 at worst
  // (measured: 1e-13).
  for (double s = 1.02; s < kSb - 0.01; s += 0.02) {
    const Stepped st = stepElement(s, 3, 2000);
    const CoulombTimes ct = coulombTimes(s);
    ASSERT_EQ(ct.regime, CoulombRegime::StickSlip);
    EXPECT_NEAR(st.t0, ct.t0, 1e-12) << "s = " << s;
    EXPECT_NEAR(st.t1, ct.t1, 1e-10) << "s = " << s;
    EXPECT_GT(ct.t1, kPi - ct.t0);  // the non-trivial root
    EXPECT_LE(ct.t1, ct.t0 + kPi);
  }
}

}  // namespace
}  // namespace metrosync
