#include "contact/averaged_response.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "base/constants.h"
#include "contact/chebyshev_table.h"
#include "contact/slip_duration.h"

namespace metrosync {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Taylor coefficients in powers of u^2 of N1(u) / u^5 and N2(u) / u^4 (see the header),
// generated with exact rational arithmetic (sympy) from the series of g(u) = (u - sin u) /
// (1 - cos u): the first ones are 2/135, 1/1134, 1/24300 and 1/72, 1/2160, 1/67200. Both series
// converge for |u| < 2 pi (g has poles at +-2 pi); at u = 2 the 20th term is below 1e-19 relative.
constexpr int kSeriesTerms = 20;
constexpr double kN1Series[kSeriesTerms] = {
    1.48148148148148154e-02, 8.81834215167548452e-04, 4.11522633744855999e-05,
    1.70577022428874276e-06, 6.55902331387340228e-08, 2.39121711784851101e-09,
    8.37283744273700719e-11, 2.83971139500738523e-12, 9.38414936870660386e-14,
    3.03474472252965054e-15, 9.63587926774924192e-17, 3.01178720013092614e-18,
    9.28574788854112773e-20, 2.82876854068354028e-21, 8.52641736568333692e-23,
    2.54581116458079906e-24, 7.53702387427630989e-26, 2.21436311521162288e-27,
    6.46075762173870148e-29, 1.87314994862820124e-30};
constexpr double kN2Series[kSeriesTerms] = {
    1.38888888888888881e-02, 4.62962962962962981e-04, 1.48809523809523809e-05,
    4.59288653733098191e-07, 1.37388943605874818e-08, 4.01476095920540372e-10,
    1.15249130074967816e-11, 3.26270358138558085e-13, 9.13444853394385983e-15,
    2.53414130104570569e-16, 6.97723234290626135e-18, 1.90874180139991254e-19,
    5.19304010768177689e-21, 1.40613052044936351e-22, 3.79156184145565337e-24,
    1.01862073293040545e-25, 2.72763625609232958e-27, 7.28265272053413540e-29,
    1.93931838087451644e-30, 5.15197771573463516e-32};
// below this u the direct formulas for N1, N2 lose more than ~2 digits to cancellation
constexpr double kSeriesMaxU = 2.0;

double horner(const double* c, int n, double x) {
  double r = c[n - 1];
  for (int k = n - 2; k >= 0; --k) r = r * x + c[k];
  return r;
}

// N1(u), N2(u) of the stick-slip formula (see the header) at u = u(q).
struct Numerators {
  double n1, n2;
};
Numerators stickSlipNumerators(double u) {
  if (u <= kSeriesMaxU) {
    const double u2 = u * u;
    return {u * u2 * u2 * horner(kN1Series, kSeriesTerms, u2),
            u2 * u2 * horner(kN2Series, kSeriesTerms, u2)};
  }
  // sin u, cos u, sin 2u from one sincos of u/2
  const double sh = std::sin(0.5 * u), ch = std::cos(0.5 * u);
  const double su = 2.0 * sh * ch, omc = 2.0 * sh * sh;
  const double g = (u - su) / omc;
  const double s2u = 2.0 * su * (1.0 - omc);
  return {(g * g - 1.0) * (2.0 * u - s2u) + 4.0 * g * su * su,
          omc * (1.0 - g * su) + 0.5 * (g * g - 1.0) * su * su};
}

// The slow flow evaluates the stick-slip response at every right-hand side. On the stick-slip
// range x = q^2 = s^2 - 1 in (0, pi^2/4] it comes from tables of H1 = N1 / q^5 and H2 = N2 / q^4
// as functions of x (u(q) is odd in q and N1, N2 are u^5, u^4 times series in u^2, so both are
// analytic in x and tend to 2 * 3^5 / 135 and 3^4 / 72 at x = 0), interpolated from the reference
// evaluation (u from the converged iteration). Measured against that reference at 220000 points
// of (1, s_b], the betas agree to 1.0e-14 relative (degree 11: 1.2e-14, 15: 7e-15: the floor is
// the rounding of the two evaluations); tests/contact/test_slip_duration.cpp checks 1e-13. The
// slow flow's local error target is 1e-8 at the default accuracy.
constexpr double kTableEnd = 0.25 * kPi * kPi;
constexpr int kTablePieces = 8;
constexpr int kTableDegree = 13;

struct ResponseTables {
  ChebyshevTable h1, h2;
};
const ResponseTables& responseTables() {
  static const ResponseTables t{
      ChebyshevTable(
          [](double x) {
            const double q = std::sqrt(x);
            return stickSlipNumerators(coulombSlipDurationReference(q)).n1 / (x * x * q);
          },
          kTableEnd, kTablePieces, kTableDegree),
      ChebyshevTable(
          [](double x) {
            return stickSlipNumerators(coulombSlipDurationReference(std::sqrt(x))).n2 / (x * x);
          },
          kTableEnd, kTablePieces, kTableDegree)};
  return t;
}

// beta1, beta2 of the stick-slip formula (eq. d2) at s > 1, written in u (see the header).
AveragedResponse stickSlipResponse(double s) {
  if (!(s > 1.0)) return {0.0, 0.0};
  const double x = (s - 1.0) * (s + 1.0);
  const double s2 = s * s;
  if (x <= kTableEnd) {
    const ResponseTables& t = responseTables();
    const double q = std::sqrt(x);
    return {x * x * q * t.h1(x) / (4.0 * kPi * s2), x * x * t.h2(x) / (kPi * s2)};
  }
  const Numerators n = stickSlipNumerators(coulombSlipDuration(std::sqrt(x)));  // continuation
  return {n.n1 / (4.0 * kPi * s2), n.n2 / (kPi * s2)};
}

// beta1 = 1/2 - 1/s^2, beta2 = (2 / (pi s)) sqrt(1 - pi^2 / (4 s^2)) (eq. d2, s > s_b).
AveragedResponse slipResponse(double s) {
  if (std::isinf(s)) return {0.5, 0.0};
  const double r = 0.5 * kPi / s;
  const double root = std::sqrt(std::fmax(0.0, (1.0 - r) * (1.0 + r)));
  return {0.5 - 1.0 / (s * s), 2.0 / (kPi * s) * root};
}

}  // namespace

const char* toString(CoulombRegime r) {
  switch (r) {
    case CoulombRegime::Stuck:
      return "stuck";
    case CoulombRegime::StickSlip:
      return "stick-slip";
    case CoulombRegime::Slip:
      return "slipping";
  }
  return "?";
}

CoulombRegime coulombRegime(double s) {
  if (s <= 1.0) return CoulombRegime::Stuck;
  if (s <= kCoulombSlipThreshold) return CoulombRegime::StickSlip;
  return CoulombRegime::Slip;
}

double coulombT0(double s) {
  if (!(s >= 1.0)) return kNaN;
  // arcsin(1/s) = atan2(1, sqrt(s^2 - 1)): no loss of accuracy as s -> 1
  return std::atan2(1.0, std::sqrt((s - 1.0) * (s + 1.0)));
}

double coulombT1(double s) {
  if (!(s >= 1.0 && s <= kCoulombSlipThreshold)) return kNaN;
  return coulombT0(s) + coulombSlipDuration(std::sqrt((s - 1.0) * (s + 1.0)));
}

double coulombTStar(double s) {
  if (!(s >= 0.5 * kPi)) return kNaN;
  if (std::isinf(s)) return 0.5 * kPi;
  // arccos(pi / (2 s)) = atan2(sqrt(s^2 - pi^2/4), pi/2)
  return std::atan2(std::sqrt((s - 0.5 * kPi) * (s + 0.5 * kPi)), 0.5 * kPi);
}

CoulombTimes coulombTimes(double s) {
  CoulombTimes t;
  t.regime = coulombRegime(s);
  t.t0 = coulombT0(s);
  if (s >= 1.0 && s <= kCoulombSlipThreshold) {
    t.u = coulombSlipDuration(std::sqrt((s - 1.0) * (s + 1.0)));  // not t1 - t0: u << t0 near s = 1
    t.t1 = t.t0 + t.u;
  } else {
    t.u = t.t1 = kNaN;
  }
  t.t_star = t.regime == CoulombRegime::Slip ? coulombTStar(s) : kNaN;
  return t;
}

AveragedResponse coulombStickSlipReference(double s) {
  if (!(s > 1.0)) return {0.0, 0.0};
  const double q = std::sqrt((s - 1.0) * (s + 1.0));
  const Numerators n = stickSlipNumerators(coulombSlipDurationReference(q));
  const double s2 = s * s;
  return {n.n1 / (4.0 * kPi * s2), n.n2 / (kPi * s2)};
}

AveragedResponse coulombResponseIn(CoulombRegime regime, double s) {
  if (std::isnan(s)) return {kNaN, kNaN};
  switch (regime) {
    case CoulombRegime::Stuck:
      return {0.0, 0.0};
    case CoulombRegime::StickSlip:
      return stickSlipResponse(s);
    case CoulombRegime::Slip:
      return slipResponse(s);
  }
  return {kNaN, kNaN};
}

AveragedResponse coulombResponse(double s) {
  return coulombResponseIn(coulombRegime(s), s);
}
double coulombBeta1(double s) {
  return coulombResponse(s).beta1;
}
double coulombBeta2(double s) {
  return coulombResponse(s).beta2;
}

AveragedResponse viscousResponse(double c) {
  // x_p'' = A (sin t + c cos t) / (1 + c^2): project on sin t and cos t
  const double d = 2.0 * (1.0 + c * c);
  return {1.0 / d, c / d};
}

// ---- the periodic solution y_p ----------------------------------------------------------------

CoulombPeriodicResponse::CoulombPeriodicResponse(double B) : B_(B) {
  if (!std::isfinite(B)) throw std::invalid_argument("CoulombPeriodicResponse: B not finite");
  // y_p(t; -B) = -y_p(t; B) (F is odd); the sign is carried by sign_of_B in reduce()
  const double b = std::fabs(B);
  times_ = coulombTimes(b);
  switch (times_.regime) {
    case CoulombRegime::Stuck:
      break;
    case CoulombRegime::StickSlip: {
      // On the forward slip, tau = t - t0 in [0, u] and B sin t - 1 = q sin tau - (1 - cos tau)
      // with q = B cos t0 = sqrt(B^2 - 1), so
      //   y'' = q sin tau - (1 - cos tau),  y' = q (1 - cos tau) - (tau - sin tau),
      //   y   = q (tau - sin tau) - (tau^2/2 - (1 - cos tau)) - c2,
      // the stuck value is c2 = y(u) = -y(0) (y(t + pi) = -y(t) makes the mean zero):
      //   c2 = (q (u - sin u) - (u^2/2 - (1 - cos u))) / 2
      // which is the appendix's c2 = (B/2)(sin t0 - sin t1) - u^2/4 + (B/2) u cos t0; its
      // c1 = 1 - c2 (= B sin t0 - c2).
      q_ = std::sqrt((b - 1.0) * (b + 1.0));
      start_ = times_.t0;
      slip_ = times_.u;
      c2_ = 0.5 * (q_ * uMinusSin(slip_) - halfSquareMinusOneMinusCos(slip_));
      break;
    }
    case CoulombRegime::Slip:
      // tau = t - t_star in [0, pi]; B sin(t_star + tau) = sigma cos tau + (pi/2) sin tau with
      // sigma = B sin t_star = sqrt(B^2 - pi^2/4)
      sigma_ = std::sqrt((b - 0.5 * kPi) * (b + 0.5 * kPi));
      start_ = times_.t_star;
      slip_ = kPi;
      break;
  }
}

CoulombPeriodicResponse::Local CoulombPeriodicResponse::reduce(double t) const {
  double tau = t - start_;
  tau -= kTwoPi * std::floor(tau / kTwoPi);
  if (tau >= kTwoPi) tau = 0.0;  // rounding of the floor
  double sign = B_ < 0.0 ? -1.0 : 1.0;
  if (tau >= kPi) {
    tau -= kPi;
    sign = -sign;
  }
  return {tau, sign};
}

double CoulombPeriodicResponse::y(double t) const {
  if (times_.regime == CoulombRegime::Stuck) return 0.0;
  const Local l = reduce(t);
  if (times_.regime == CoulombRegime::StickSlip) {
    if (l.tau >= slip_) return l.sign * c2_;
    return l.sign * (q_ * uMinusSin(l.tau) - halfSquareMinusOneMinusCos(l.tau) - c2_);
  }
  const double tau = l.tau;
  return l.sign *
         (-sigma_ * std::cos(tau) - 0.5 * kPi * std::sin(tau) - 0.5 * tau * tau + 0.5 * kPi * tau);
}

double CoulombPeriodicResponse::ydot(double t) const {
  if (times_.regime == CoulombRegime::Stuck) return 0.0;
  const Local l = reduce(t);
  if (times_.regime == CoulombRegime::StickSlip) {
    if (l.tau >= slip_) return 0.0;
    return l.sign * (q_ * oneMinusCos(l.tau) - uMinusSin(l.tau));
  }
  const double tau = l.tau;
  return l.sign * (sigma_ * std::sin(tau) + 0.5 * kPi * oneMinusCos(tau) - tau);
}

double CoulombPeriodicResponse::yddot(double t) const {
  if (times_.regime == CoulombRegime::Stuck) return 0.0;
  const Local l = reduce(t);
  if (times_.regime == CoulombRegime::StickSlip) {
    if (l.tau >= slip_) return 0.0;
    return l.sign * (q_ * std::sin(l.tau) - oneMinusCos(l.tau));
  }
  const double tau = l.tau;
  return l.sign * (sigma_ * std::cos(tau) + 0.5 * kPi * std::sin(tau) - 1.0);
}

PlatformMode CoulombPeriodicResponse::mode(double t) const {
  if (times_.regime == CoulombRegime::Stuck) return PlatformMode::Stuck;
  const Local l = reduce(t);
  if (l.tau >= slip_) return PlatformMode::Stuck;
  return l.sign > 0.0 ? PlatformMode::SlipPositive : PlatformMode::SlipNegative;
}

double coulombYp(double t, double B) {
  return CoulombPeriodicResponse(B).y(t);
}
double coulombYpDot(double t, double B) {
  return CoulombPeriodicResponse(B).ydot(t);
}
double coulombYpDDot(double t, double B) {
  return CoulombPeriodicResponse(B).yddot(t);
}

}  // namespace metrosync
