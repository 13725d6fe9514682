// The platform's averaged response to a sinusoidal drive, for each friction law: what the slow
// flow needs from the fast motion of the platform (paper appendices "ac" and "ad").
//
// Scaled platform equation at leading order, drive amplitude A, drive phase set to zero:
//   Coulomb:  x'' = mu F + A sin t      (F the unit Coulomb force, eq. b1; y = x / mu, B = A / mu)
//   viscous:  x'' = -c x' + A sin t
// The periodic response x_p defines the two averaged coefficients of the slow flow (e3.1a-c):
//   beta1 = (1 / (2 pi A)) int_0^{2 pi} x_p''(t) sin t dt    (energy exchange between pendulums)
//   beta2 = (1 / (2 pi A)) int_0^{2 pi} x_p''(t) cos t dt    (energy taken out by the platform)
// For Coulomb friction they depend on s = B = A / mu only (eqs. d1, d2).
//
// Three Coulomb regimes (appendix "ac"), with s_b = sqrt(1 + pi^2 / 4):
//   Stuck      s <= 1        friction holds the platform: y_p = 0, beta = (0, 0)
//   StickSlip  1 < s <= s_b  slips on (t0, t1), sticks on (t1, t0 + pi), then the mirror image
//   Slip       s > s_b       slips all the time, reversing at t_star and t_star + pi
//
// Numerics: the stick time t1 is found from u = t1 - t0, the root in (pi - 2 t0, pi] of
//   g(u) = (u - sin u) / (1 - cos u) = sqrt(s^2 - 1)
// (the paper's cos t1 - cos t0 + (t1 - t0)/s = 0 with sin t0 = 1/s, cos t0 = sqrt(1 - 1/s^2);
// that form has the trivial double root t1 = t0 and cancels badly as s -> 1+). In the stick-slip
// regime beta1, beta2 are functions of u alone,
//   beta1 = N1(u) / (4 pi s^2),  N1 = (g^2 - 1)(2u - sin 2u) + 4 g sin^2 u   ~ 2 u^5 / 135
//   beta2 = N2(u) / (pi s^2),    N2 = (1 - cos u)(1 - g sin u) + (g^2 - 1) sin^2(u) / 2 ~ u^4 / 72
// evaluated from their Taylor series for small u, so that they keep full relative accuracy as
// s -> 1+ (s - 1 ~ u^2 / 18). u comes from contact/slip_duration.h; on 1 < s <= s_b the betas
// are interpolated (to ~1e-14 relative) from tables of N1 / q^5 and N2 / q^4 in q^2.
#pragma once

#include "contact/platform_mode.h"

namespace metrosync {

// s_b = sqrt(1 + pi^2/4): boundary between stick-slip and pure slip.
constexpr double kCoulombSlipThreshold = 1.8620958891185866;

enum class CoulombRegime { Stuck, StickSlip, Slip };

const char* toString(CoulombRegime r);

// Regime of the Coulomb platform at drive strength s = A / mu (s = +inf for mu = 0).
CoulombRegime coulombRegime(double s);

// The averaged coefficients of the slow flow.
struct AveragedResponse {
  double beta1 = 0.0;
  double beta2 = 0.0;
};

// Slip and stick instants of y_p (eq. d1). Fields that do not apply to the regime are NaN.
struct CoulombTimes {
  CoulombRegime regime = CoulombRegime::Stuck;
  double t0 = 0.0;      // first slip, arcsin(1/s)            (s >= 1)
  double t1 = 0.0;      // first stick, t0 + u                (1 <= s <= s_b)
  double u = 0.0;       // slip duration t1 - t0 in [0, pi]   (1 <= s <= s_b)
  double t_star = 0.0;  // slip reversal, arccos(pi / (2 s))  (s > s_b)
};
CoulombTimes coulombTimes(double s);

// eq. d1: t0(s) = arcsin(1/s) for s >= 1, NaN below.
double coulombT0(double s);
// eq. d1: t1(s) for 1 <= s <= s_b (t1(1) = t0(1) = pi/2, t1(s_b) = t0 + pi), NaN outside.
double coulombT1(double s);
// t_star(s) = arccos(pi / (2 s)) for s >= pi/2 (meaningful for s > s_b), NaN below.
double coulombTStar(double s);

// eq. d2, continuous across s = 1 and s = s_b; s = +inf gives (1/2, 0), s <= 1 gives (0, 0).
AveragedResponse coulombResponse(double s);
double coulombBeta1(double s);
double coulombBeta2(double s);

// eq. d2 with the formula of a given regime, continued beyond the regime's range (Stuck: 0;
// StickSlip: 0 for s <= 1, the analytic continuation in u for s > s_b; Slip: for s >= pi/2,
// sqrt clamped at 0 below). For an integrator that keeps the regime fixed over a step and
// switches it at a located event.
AveragedResponse coulombResponseIn(CoulombRegime regime, double s);

// The stick-slip formula of eq. d2 at s > 1 evaluated from u = t1 - t0 of the converged
// iteration (contact/slip_duration.h), the function coulombResponseIn(StickSlip, s) interpolates
// on 1 < s <= s_b (the slow flow's hot path; see averaged_response.cpp). (0, 0) for s <= 1.
AveragedResponse coulombStickSlipReference(double s);

// Viscous platform x'' = -c x' + A sin t: beta1 = 1 / (2 (1 + c^2)), beta2 = c / (2 (1 + c^2)).
AveragedResponse viscousResponse(double c);

// The zero-mean 2 pi-periodic solution y_p(t; B) of y'' = F(y', B sin t) + B sin t (eq. c1,
// unit Coulomb friction, appendix "ac"); y_p(t + pi) = -y_p(t). Multiply by mu (and shift t by
// the drive phase) for the platform: x_0(t) = mu y_p(t + phi; A / mu).
class CoulombPeriodicResponse {
 public:
  explicit CoulombPeriodicResponse(double B);

  double y(double t) const;
  double ydot(double t) const;
  double yddot(double t) const;  // one-sided (from the right) at the stick and reversal instants
  // Platform mode on [t, t+): slips on [start, start + slip length) of each half period.
  PlatformMode mode(double t) const;

  double B() const { return B_; }
  const CoulombTimes& times() const { return times_; }
  // First slip of the period: t0 (stick-slip) or t_star (slip); 0 when stuck.
  double slipStart() const { return start_; }
  // Duration of one slip: u (stick-slip), pi (slip), 0 (stuck).
  double slipLength() const { return slip_; }

 private:
  struct Local {
    double tau;   // time since the start of the current half period's slip, in [0, pi)
    double sign;  // +1 first half (slipping forwards), -1 second half
  };
  Local reduce(double t) const;

  double B_;
  CoulombTimes times_;
  double start_ = 0.0;
  double slip_ = 0.0;
  // stick-slip: q = sqrt(B^2 - 1), stuck value c2; slip: sigma = sqrt(B^2 - pi^2/4)
  double q_ = 0.0, c2_ = 0.0, sigma_ = 0.0;
};

double coulombYp(double t, double B);
double coulombYpDot(double t, double B);
double coulombYpDDot(double t, double B);

}  // namespace metrosync
