// The platform's averaged response (contact/averaged_response.h) against independent truth:
// Fourier projections of the closed-form acceleration by quadrature, the ODE the periodic solution
// must solve, the appendix's own formulas for y_p, a direct root of the paper's t1 equation, the
// small-(s - 1) asymptotics, and a time-stepped viscous platform.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "base/constants.h"
#include "contact/averaged_response.h"
#include "contact/friction_law.h"
#include "contact/law_registry.h"

namespace metrosync {
namespace {

const double kSb = std::sqrt(1.0 + kPi * kPi / 4.0);

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n): exact for polynomials of degree
// 2n - 1; on the smooth pieces of y_p'' sin t (entire functions) 40 nodes reach machine precision.
struct Gauss {
  std::vector<double> x, w;
  explicit Gauss(int n) : x(n), w(n) {
    for (int i = 0; i < n; ++i) {
      double z = std::cos(kPi * (i + 0.75) / (n + 0.5));
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = z;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        const double dp = n * (z * p1 - p0) / (z * z - 1.0);
        const double dz = p1 / dp;
        z -= dz;
        if (std::fabs(dz) < 1e-16) {
          x[i] = z;
          w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
          break;
        }
        x[i] = z;
        w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
      }
    }
  }
  template <class F>
  double integrate(F&& f, double a, double b) const {
    const double m = 0.5 * (a + b), r = 0.5 * (b - a);
    double s = 0.0;
    for (size_t i = 0; i < x.size(); ++i) s += w[i] * f(m + r * x[i]);
    return s * r;
  }
};

const Gauss& gauss() {
  static const Gauss g(40);
  return g;
}

// The instants where y_p'' may jump, over one period starting at the first slip.
std::vector<double> breakpoints(const CoulombPeriodicResponse& yp) {
  const double a = yp.slipStart(), L = yp.slipLength();
  if (yp.times().regime == CoulombRegime::Stuck) return {0.0, kPi / 2, kPi, 1.5 * kPi, 2 * kPi};
  return {a, a + L, a + kPi, a + kPi + L, a + 2 * kPi};
}

// beta1, beta2 = (1 / (2 pi s)) int y_p'' (sin t, cos t) over a period (the definition of the
// averaged coefficients with x = mu y, A = mu s; appendix "ad").
AveragedResponse projectAcceleration(double s) {
  CoulombPeriodicResponse yp(s);
  const auto b = breakpoints(yp);
  double ps = 0.0, pc = 0.0;
  for (size_t k = 0; k + 1 < b.size(); ++k) {
    if (b[k + 1] <= b[k]) continue;
    ps += gauss().integrate([&](double t) { return yp.yddot(t) * std::sin(t); }, b[k], b[k + 1]);
    pc += gauss().integrate([&](double t) { return yp.yddot(t) * std::cos(t); }, b[k], b[k + 1]);
  }
  return {ps / (2 * kPi * s), pc / (2 * kPi * s)};
}

std::vector<double> sGrid() {
  std::vector<double> s;
  for (int k = 0; k <= 380; ++k) s.push_back(0.5 + 0.025 * k);  // 0.5 .. 10
  for (double d : {1e-6, 1e-9, 1e-3}) {
    s.push_back(1.0 + d);
    s.push_back(1.0 - d);
    s.push_back(kSb + d);
    s.push_back(kSb - d);
  }
  s.push_back(kSb);
  s.push_back(1.0);
  return s;
}

TEST(CoulombBetas, MatchFourierProjectionsOfTheClosedFormAcceleration) {
  // Gauss quadrature on each smooth piece is exact to rounding, so the only error is rounding in
  // the formulas and the sums (~1e-16 relative to the O(1) pieces): 1e-13 leaves a wide margin
  // and is far tighter than the 1e-9 the slow flow needs.
  double worst = 0.0;
  for (double s : sGrid()) {
    const AveragedResponse q = projectAcceleration(s);
    const AveragedResponse b = coulombResponse(s);
    EXPECT_NEAR(b.beta1, q.beta1, 1e-13) << "s = " << s;
    EXPECT_NEAR(b.beta2, q.beta2, 1e-13) << "s = " << s;
    EXPECT_EQ(coulombBeta1(s), b.beta1);
    EXPECT_EQ(coulombBeta2(s), b.beta2);
    worst = std::max({worst, std::fabs(b.beta1 - q.beta1), std::fabs(b.beta2 - q.beta2)});
  }
  RecordProperty("max_abs_beta_minus_quadrature", std::to_string(worst));
}

TEST(CoulombBetas, KeepRelativeAccuracyAsSApproachesOne) {
  // beta1 ~ (s-1)^{5/2}, beta2 ~ (s-1)^2 vanish at s = 1; the naive formula (eq. d2) loses all
  // digits there. Quadrature of y_p'' sin t would lose them too (sin t ~ 1 on the slip, and
  // y_p'' integrates to zero over it), so the projection on sin t is taken as
  //   int y_p'' (sin t - 1) dt,  sin t - 1 = -2 sin^2(pi/4 - t/2)  (no cancellation)
  // using int_slip y_p'' = y_p'(t1) - y_p'(t0) = 0 (checked in SolvesTheCoulombOde). What is
  // left is rounding in the slip-local time (~1e-16 / u relative in y_p''): ~1e-13 at
  // s - 1 = 1e-6 (u ~ 4e-3). 1e-10 relative checks that the library keeps 10 digits there.
  for (double d : {1e-2, 1e-4, 1e-6, 1e-8}) {
    const double s = 1.0 + d;
    CoulombPeriodicResponse yp(s);
    const auto b = breakpoints(yp);
    double ps = 0.0, pc = 0.0;
    for (size_t k = 0; k + 1 < b.size(); ++k) {
      if (b[k + 1] <= b[k]) continue;
      const double one = k < 2 ? 1.0 : -1.0;  // sin t = -1 on the second half's slip
      ps += gauss().integrate(
          [&](double t) {
            const double h = std::sin(0.5 * t - 0.25 * kPi * one);  // sin t -+ 1 = -+2 h^2
            return yp.yddot(t) * (-2.0 * one * h * h);
          },
          b[k], b[k + 1]);
      pc += gauss().integrate([&](double t) { return yp.yddot(t) * std::cos(t); }, b[k], b[k + 1]);
    }
    const AveragedResponse r = coulombResponse(s);
    EXPECT_NEAR(r.beta1 / (ps / (2 * kPi * s)), 1.0, 1e-10) << "s - 1 = " << d;
    EXPECT_NEAR(r.beta2 / (pc / (2 * kPi * s)), 1.0, 1e-10) << "s - 1 = " << d;
  }
}

TEST(CoulombBetas, LeadingBehaviourAtTheStickThreshold) {
  // From the appendix equations by Taylor expansion (done by hand): u = t1 - t0 ~ 3 sqrt(2 d),
  // beta1 ~ u^5 / (270 pi), beta2 ~ u^4 / (72 pi), so with d = s - 1 -> 0
  //   beta2 / d^2 -> 4.5 / pi,  beta1 / d^{5/2} -> 0.9 * 2^{5/2} / pi.
  // The relative corrections are O(d) (~1e-8 at d = 1e-8, 1e-6 at d = 1e-6): tolerance 1e-5.
  for (double d : {1e-6, 1e-8}) {
    const AveragedResponse b = coulombResponse(1.0 + d);
    EXPECT_NEAR(b.beta2 / (d * d) / (4.5 / kPi), 1.0, 1e-5);
    EXPECT_NEAR(b.beta1 / std::pow(d, 2.5) / (0.9 * std::pow(2.0, 2.5) / kPi), 1.0, 1e-5);
  }
}

TEST(CoulombBetas, ContinuousAcrossBothRegimeBoundaries) {
  // |beta'| <= 1 on [0.5, 10] (beta2 peaks at ~0.2, beta1 rises by 1/2 over s in (1, 3)): a jump
  // would show as a difference much larger than 2 d.
  for (double d : {1e-6, 1e-9}) {
    for (double s0 : {1.0, kSb}) {
      const AveragedResponse lo = coulombResponse(s0 - d), hi = coulombResponse(s0 + d);
      EXPECT_LE(std::fabs(hi.beta1 - lo.beta1), 2 * d) << "s0 = " << s0;
      EXPECT_LE(std::fabs(hi.beta2 - lo.beta2), 2 * d) << "s0 = " << s0;
    }
  }
  // at s_b both regimes' formulas give the same numbers (u = pi exactly there): rounding only
  const AveragedResponse a = coulombResponseIn(CoulombRegime::StickSlip, kSb);
  const AveragedResponse b = coulombResponseIn(CoulombRegime::Slip, kSb);
  EXPECT_NEAR(a.beta1, b.beta1, 1e-14);
  EXPECT_NEAR(a.beta2, b.beta2, 1e-14);
  EXPECT_NEAR(b.beta1, 0.5 - 1.0 / (kSb * kSb), 1e-15);
  EXPECT_NEAR(b.beta2, 2.0 / (kPi * kSb * kSb), 1e-15);  // sin t_star = 1/s_b there
}

TEST(CoulombBetas, LimitsAndMonotonicity) {
  for (double s : {0.0, 0.3, 0.999999, 1.0}) {
    EXPECT_EQ(coulombBeta1(s), 0.0);
    EXPECT_EQ(coulombBeta2(s), 0.0);
  }
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(coulombBeta1(inf), 0.5);  // mu = 0: the free platform, x'' = A sin t
  EXPECT_EQ(coulombBeta2(inf), 0.0);
  // large s: beta1 = 1/2 - 1/s^2 exactly, beta2 ~ 2 / (pi s)
  EXPECT_NEAR(coulombBeta1(1e4), 0.5, 1.1e-8);
  EXPECT_NEAR(coulombBeta2(1e4) * kPi * 1e4 / 2.0, 1.0, 1e-7);
  // beta1 rises monotonically from 0 to 1/2; beta2 >= 0 rises to its peak at s = pi / sqrt 2
  // (where d/ds of (1/s) sqrt(1 - pi^2/(4 s^2)) vanishes), then falls
  double prev1 = 0.0, prev2 = 0.0;
  const double peak = kPi / std::sqrt(2.0);
  for (double s = 0.5; s < 60.0; s += 0.01) {
    const AveragedResponse b = coulombResponse(s);
    EXPECT_GE(b.beta1, prev1) << s;
    EXPECT_LT(b.beta1, 0.5);
    EXPECT_GE(b.beta2, 0.0);
    if (s < peak - 0.01) {
      EXPECT_GE(b.beta2, prev2) << s;
    }
    if (s > peak + 0.01) {
      EXPECT_LE(b.beta2, prev2) << s;
    }
    prev1 = b.beta1;
    prev2 = b.beta2;
  }
}

// t1 of the paper's equation cos t1 - cos t0 + (t1 - t0)/s = 0 by plain bisection on
// [pi - t0, pi + t0] (the trivial root t1 = t0 lies outside it).
double t1ByBisection(double s) {
  const double t0 = std::asin(1.0 / s);
  auto f = [&](double t) { return std::cos(t) - std::cos(t0) + (t - t0) / s; };
  double a = kPi - t0, b = kPi + t0;
  for (int it = 0; it < 200; ++it) {
    const double m = 0.5 * (a + b);
    ((f(m) > 0) == (f(a) > 0) ? a : b) = m;
  }
  return 0.5 * (a + b);
}

TEST(CoulombTimes, StickTimeProperties) {
  double prev_t0 = 10.0, prev_t1 = -1.0;
  for (double s = 1.0005; s <= kSb; s += 0.0005) {
    const double t0 = coulombT0(s), t1 = coulombT1(s);
    EXPECT_NEAR(t0, std::asin(1.0 / s), 1e-14);
    // appendix "ac", properties 1, 2, 4 (t0 decreasing, t1 increasing, pi - t0 <= t1 <= t0 + pi)
    EXPECT_LT(t0, prev_t0);
    EXPECT_GT(t1, prev_t1);
    EXPECT_GE(t1, kPi - t0 - 1e-14);
    EXPECT_LE(t1, t0 + kPi + 1e-14);
    // the paper's equation, solved directly: the root's condition number is 1/|f'(t1)| =
    // 1 / |1/s - sin t1| <= ~1e3 here, so bisection gives t1 to ~1e-13 at worst
    EXPECT_NEAR(t1, t1ByBisection(s), 1e-11) << "s = " << s;
    prev_t0 = t0;
    prev_t1 = t1;
  }
  // property 3: t1 = t0 + pi at s_b
  EXPECT_NEAR(coulombT1(kSb), coulombT0(kSb) + kPi, 1e-12);
  EXPECT_NEAR(coulombT1(1.0), kPi / 2, 1e-15);
  EXPECT_TRUE(std::isnan(coulombT1(0.9)));
  EXPECT_TRUE(std::isnan(coulombT1(kSb + 1e-3)));
  // t_star = arccos(pi / (2 s)) and t_star(s_b) = t0(s_b)
  EXPECT_NEAR(coulombTStar(3.0), std::acos(kPi / 6.0), 1e-15);
  EXPECT_NEAR(coulombTStar(kSb), coulombT0(kSb), 1e-14);
}

TEST(CoulombTimes, SlipDurationNearTheStickThreshold) {
  // Inverting g(u) = u/3 + u^3/90 + u^5/2520 + ... = q = sqrt(s^2 - 1) by hand gives
  // u = 3q - 0.9 q^3 + (0.81 - 3^6/2520) q^5 + O(q^7); at q <= 1.5e-3 the q^7 term is < 1e-19
  // relative to u, so the comparison is limited by rounding: 1e-13 relative.
  for (double d : {1e-6, 1e-8, 1e-10, 1e-12}) {
    const double s = 1.0 + d;
    const double ds = s - 1.0;  // exact (Sterbenz); d itself is not representable in 1 + d
    const double q = std::sqrt(ds * (2.0 + ds));
    const double u = 3 * q - 0.9 * q * q * q + (0.81 - 729.0 / 2520.0) * std::pow(q, 5);
    const CoulombTimes t = coulombTimes(s);
    EXPECT_EQ(t.regime, CoulombRegime::StickSlip);
    EXPECT_NEAR(t.u / u, 1.0, 1e-13) << "s - 1 = " << d;
  }
}

// The appendix's y_p (moderate forcing, with its c1, c2; strong forcing), written out directly.
double appendixYp(double t, double B) {
  if (B <= 1.0) return 0.0;
  if (B <= kSb) {
    const double t0 = std::asin(1.0 / B), t1 = t1ByBisection(B), u = t1 - t0;
    const double c1 =
        B / 2 * std::sin(t1) + B / 2 * std::sin(t0) + u * u / 4 - B / 2 * u * std::cos(t0);
    const double c2 =
        -B / 2 * std::sin(t1) + B / 2 * std::sin(t0) - u * u / 4 + B / 2 * u * std::cos(t0);
    t = t0 + std::fmod(std::fmod(t - t0, 2 * kPi) + 2 * kPi, 2 * kPi);  // into [t0, t0 + 2 pi)
    if (t <= t1)
      return -B * std::sin(t) - (t - t0) * (t - t0) / 2 + B * (t - t0) * std::cos(t0) + c1;
    if (t <= t0 + kPi) return c2;
    if (t <= t1 + kPi)
      return -B * std::sin(t) + (t - t0 - kPi) * (t - t0 - kPi) / 2 -
             B * (t - t0 - kPi) * std::cos(t0) - c1;
    return -c2;
  }
  const double ts = std::acos(kPi / (2 * B));
  t = ts + std::fmod(std::fmod(t - ts, 2 * kPi) + 2 * kPi, 2 * kPi);
  if (t <= ts + kPi)
    return -B * std::sin(t) - (t - ts) * (t - ts) / 2 + B * (t - ts) * std::cos(ts);
  return -B * std::sin(t) + (t - ts - kPi) * (t - ts - kPi) / 2 - B * (t - ts - kPi) * std::cos(ts);
}

const double kBs[] = {0.5,  1.0, 1.001, 1.05, 1.2, 1.4, 1.6, 1.8, 1.8620958891185866,
                      1.87, 2.0, 2.5,   4.0,  10.0};

TEST(CoulombPeriodicResponse, AgreesWithTheAppendixFormulas) {
  // The appendix's formulas (checked by hand to be right: c1 = B sin t0 - c2 makes y continuous
  // at t0, y(t + pi) = -y(t) gives zero mean) evaluated independently; they cancel to ~1e-15 B^2.
  for (double B : kBs) {
    for (double t = -7.0; t < 14.0; t += 0.01) {
      EXPECT_NEAR(coulombYp(t, B), appendixYp(t, B), 2e-12 * B * B) << "B = " << B << " t = " << t;
    }
  }
}

TEST(CoulombPeriodicResponse, SolvesTheCoulombOde) {
  for (double B : kBs) {
    CoulombPeriodicResponse yp(B);
    const auto bps = breakpoints(yp);
    auto nearBreak = [&](double t, double d) {
      for (double k = -2; k <= 2; ++k)
        for (double b : bps)
          if (std::fabs(t - (b + 2 * kPi * k)) < d) return true;
      return false;
    };
    const double h = 1e-4;  // central differences: truncation h^2 |y'''| / 6 ~ 1e-9 B, rounding
                            // 1e-16 |y| / h ~ 1e-12 B^2: tolerance 1e-7 (1 + B^2)
    for (double t = -6.0; t < 13.0; t += 0.0137) {
      const double y = yp.y(t), v = yp.ydot(t), a = yp.yddot(t);
      const double drive = B * std::sin(t);
      // periodic, antiperiodic over half a period (zero mean follows)
      EXPECT_NEAR(yp.y(t + 2 * kPi), y, 1e-12 * (1 + B * B));
      EXPECT_NEAR(yp.y(t + kPi), -y, 1e-12 * (1 + B * B));
      if (nearBreak(t, 2 * h)) continue;
      EXPECT_NEAR((yp.y(t + h) - yp.y(t - h)) / (2 * h), v, 1e-7 * (1 + B * B)) << B << " " << t;
      EXPECT_NEAR((yp.ydot(t + h) - yp.ydot(t - h)) / (2 * h), a, 1e-7 * (1 + B * B));
      const PlatformMode m = yp.mode(t);
      if (m == PlatformMode::Stuck) {
        // stuck: at rest, and friction can hold the drive (|F| = |B sin t| <= 1)
        EXPECT_EQ(v, 0.0);
        EXPECT_EQ(a, 0.0);
        EXPECT_LE(std::fabs(drive), 1.0 + 1e-12) << "B = " << B << " t = " << t;
      } else {
        // slipping: friction -sign(y') opposes the motion, y'' = F + B sin t
        const double dir = m == PlatformMode::SlipPositive ? 1.0 : -1.0;
        EXPECT_GT(v * dir, 0.0) << "B = " << B << " t = " << t;
        EXPECT_NEAR(a, -dir + drive, 1e-13 * (1 + B));
      }
    }
    // continuity of y and y' at every switch (y'' may jump), and rest at the switches
    for (double b : bps) {
      const double e = 1e-9;
      EXPECT_NEAR(yp.y(b - e), yp.y(b + e), 1e-8 * (1 + B));
      EXPECT_NEAR(yp.ydot(b - e), yp.ydot(b + e), 1e-8 * (1 + B));
      EXPECT_NEAR(yp.ydot(b), 0.0, 1e-13 * (1 + B));
    }
    // zero mean (quadrature on the smooth pieces: rounding only)
    double mean = 0.0;
    for (size_t k = 0; k + 1 < bps.size(); ++k)
      if (bps[k + 1] > bps[k])
        mean += gauss().integrate([&](double t) { return yp.y(t); }, bps[k], bps[k + 1]);
    EXPECT_NEAR(mean / (2 * kPi), 0.0, 1e-14 * (1 + B * B)) << "B = " << B;
  }
}

TEST(CoulombPeriodicResponse, NegativeDriveMirrors) {
  for (double t = 0.0; t < 7.0; t += 0.1) {
    EXPECT_EQ(coulombYp(t, -1.4), -coulombYp(t, 1.4));
    EXPECT_EQ(coulombYpDot(t, -2.0), -coulombYpDot(t, 2.0));
    EXPECT_EQ(coulombYpDDot(t, -2.0), -coulombYpDDot(t, 2.0));
  }
}

// x'' = -c x' + A sin t stepped with RK4 (only v = x' matters) until the transient (~e^{-c t}) is
// gone, then x'' is projected on sin t and cos t over one more period with the trapezoidal rule
// (spectrally accurate for a smooth periodic integrand).
AveragedResponse viscousByTimeStepping(double c, double A) {
  const int per_period = 4000;
  const double dt = 2 * kPi / per_period;
  const int periods = static_cast<int>(40.0 / c / (2 * kPi)) + 2;  // e^{-40} of transient left
  auto acc = [&](double t, double v) { return -c * v + A * std::sin(t); };
  auto step = [&](double t, double v) {
    const double k1 = acc(t, v), k2 = acc(t + dt / 2, v + dt / 2 * k1);
    const double k3 = acc(t + dt / 2, v + dt / 2 * k2), k4 = acc(t + dt, v + dt * k3);
    return v + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  };
  double v = 0.0;
  for (int k = 0; k < periods * per_period; ++k) v = step((k % per_period) * dt, v);
  double ps = 0.0, pc = 0.0;
  for (int k = 0; k < per_period; ++k) {
    const double t = k * dt, a = acc(t, v);
    ps += a * std::sin(t) * dt;
    pc += a * std::cos(t) * dt;
    v = step(t, v);
  }
  return {ps / (2 * kPi * A), pc / (2 * kPi * A)};
}

TEST(ViscousResponse, MatchesATimeSteppedPlatform) {
  // RK4 at 4000 steps per period: global error ~ (2 pi / 4000)^4 ~ 1e-11; transient e^{-40}:
  // tolerance 1e-9.
  for (double c : {0.1, 0.5, 2.0}) {
    const AveragedResponse ts = viscousByTimeStepping(c, 1.7);
    const AveragedResponse b = viscousResponse(c);
    EXPECT_NEAR(b.beta1, ts.beta1, 1e-9) << "c = " << c;
    EXPECT_NEAR(b.beta2, ts.beta2, 1e-9) << "c = " << c;
  }
  // c -> 0 is the free platform: the same projection as Coulomb with mu = 0
  EXPECT_EQ(viscousResponse(0.0).beta1, 0.5);
  EXPECT_EQ(viscousResponse(0.0).beta2, 0.0);
}

TEST(AveragedResponse, EachLawCarriesItsOwn) {
  auto at = [](const FrictionLaw& law, double A) { return law.slowResponse().at(A); };
  const AveragedResponse c = at(FrictionLaw::coulomb(0.4), 0.6);
  EXPECT_EQ(c.beta1, coulombBeta1(0.6 / 0.4));
  EXPECT_EQ(c.beta2, coulombBeta2(0.6 / 0.4));
  const AveragedResponse free = at(FrictionLaw::coulomb(0.0), 0.6);
  EXPECT_EQ(free.beta1, 0.5);
  EXPECT_EQ(free.beta2, 0.0);
  const AveragedResponse none = at(FrictionLaw::none(), 2.0);
  EXPECT_EQ(none.beta1, 0.5);
  EXPECT_EQ(none.beta2, 0.0);
  const AveragedResponse fixed = at(FrictionLaw::fixed(), 2.0);
  EXPECT_EQ(fixed.beta1, 0.0);
  EXPECT_EQ(fixed.beta2, 0.0);
  const AveragedResponse visc = at(FrictionLaw::viscous(0.5), 2.0);
  EXPECT_DOUBLE_EQ(visc.beta1, 1.0 / 2.5);
  EXPECT_DOUBLE_EQ(visc.beta2, 0.5 / 2.5);
  EXPECT_THROW(at(FrictionLaw::coulomb(-0.1), 1.0), std::invalid_argument);
  // static friction: Coulomb's response at mu_static == mu, none derived above it
  const AveragedResponse equal = at(FrictionLaw(staticCoulombLaw(), {0.4, 0.4}), 0.6);
  EXPECT_EQ(equal.beta1, c.beta1);
  EXPECT_EQ(equal.beta2, c.beta2);
  const FrictionLaw above(staticCoulombLaw(), {0.4, 0.5});
  EXPECT_FALSE(above.slowResponse().available());
  EXPECT_THROW(at(above, 0.6), std::invalid_argument);
}

}  // namespace
}  // namespace metrosync
