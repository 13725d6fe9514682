// The slip function g(u), its inverse u(q) (a Chebyshev start and one Newton step) and the
// cancellation-free elementary functions (see contact/slip_duration.h).
#include "contact/slip_duration.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "base/constants.h"
#include "contact/chebyshev_table.h"

namespace metrosync {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Taylor coefficients of (u - sin u) / u^3 and (u^2/2 - (1 - cos u)) / u^4 in powers of u^2:
// (-1)^j / (2j + 3)! and (-1)^j / (2j + 4)!. Alternating, terms falling by >= 20x below |u| = 1:
// 12 terms reach 1e-30.
constexpr int kSmallTerms = 12;
constexpr std::array<double, kSmallTerms> taylor(int first) {
  std::array<double, kSmallTerms> c{};
  double f = 1.0;
  for (int k = 2; k <= first; ++k) f *= k;
  for (int j = 0; j < kSmallTerms; ++j) {
    c[j] = (j % 2 ? -1.0 : 1.0) / f;
    f *= (first + 2.0 * j + 1.0) * (first + 2.0 * j + 2.0);
  }
  return c;
}
constexpr std::array<double, kSmallTerms> kUMinusSin = taylor(3);
constexpr std::array<double, kSmallTerms> kHalfSquare = taylor(4);

template <size_t n>
double horner(const std::array<double, n>& c, double x) {
  double r = c[n - 1];
  for (int k = static_cast<int>(n) - 2; k >= 0; --k) r = r * x + c[k];
  return r;
}

// g(u) - q and g'(u) = 1 - g cot(u/2) from one sincos of u/2 (0 < u < 2 pi)
struct SlipResidual {
  double f, dg;
};
SlipResidual slipResidual(double u, double q) {
  const double sh = std::sin(0.5 * u), ch = std::cos(0.5 * u);
  const double omc = 2.0 * sh * sh;  // 1 - cos u
  const double ums = std::fabs(u) < 1.0 ? u * u * u * horner(kUMinusSin, u * u) : u - 2.0 * sh * ch;
  const double g = ums / omc;
  return {g - q, 1.0 - g * ch / sh};
}

// The start of coulombSlipDuration: u(q) / q as a function of x = q^2 on [0, (pi/2)^2] (it is
// even in q and analytic there: g' > 0 on [0, pi]), interpolated at the Chebyshev points of
// kPieces equal pieces, kDegree + 1 nodes each, from the reference iteration. u(q)/q falls from 3
// at q = 0 to 2 at q = pi/2; the interpolant's relative error, measured against the reference at
// 220000 points of (0, pi/2], is 2e-15 at worst, so the Newton step that follows only removes
// rounding (its own error is ~u g''/(2 g') times the square of the start's).
constexpr int kPieces = 8;
constexpr int kDegree = 11;
constexpr double kTableEnd = 0.25 * kPi * kPi;
// below this q, u = 3q to double precision (and u^3 would underflow in g)
constexpr double kTinyQ = 1e-20;

const ChebyshevTable& slipDurationTable() {
  static const ChebyshevTable table(
      [](double x) {
        const double q = std::sqrt(x);
        return coulombSlipDurationReference(q) / q;
      },
      kTableEnd, kPieces, kDegree);
  return table;
}

}  // namespace

double oneMinusCos(double u) {
  const double h = std::sin(0.5 * u);
  return 2.0 * h * h;
}

double uMinusSin(double u) {
  if (std::fabs(u) >= 1.0) return u - std::sin(u);
  return u * u * u * horner(kUMinusSin, u * u);
}

double halfSquareMinusOneMinusCos(double u) {
  if (std::fabs(u) >= 1.0) return 0.5 * u * u - oneMinusCos(u);
  const double u2 = u * u;
  return u2 * u2 * horner(kHalfSquare, u2);
}

double coulombSlipFunction(double u) {
  return uMinusSin(u) / oneMinusCos(u);
}

double coulombSlipDurationReference(double q) {
  if (!(q > 0.0)) return 0.0;
  if (!std::isfinite(q)) return kNaN;
  double u;
  if (3.0 * q < kPi) {
    u = 3.0 * q;  // g(u) >= u/3 (all Taylor coefficients are positive), so g(3q) >= q
  } else if (q <= 0.5 * kPi) {
    u = kPi;  // g(pi) = pi/2
  } else {
    // analytic continuation beyond s_b: bracket by bisection, keep the right end
    double a = kPi, b = kTwoPi;
    for (int it = 0; it < 60; ++it) {
      const double m = 0.5 * (a + b);
      (coulombSlipFunction(m) >= q ? b : a) = m;
    }
    u = b;
  }
  for (int it = 0; it < 100; ++it) {
    const double g = coulombSlipFunction(u);
    const double f = g - q;
    if (f <= 0.0) break;
    // g'(u) = 1 - g cot(u/2) = 1 - g sin u / (1 - cos u)
    const double dg = 1.0 - g * std::sin(u) / oneMinusCos(u);
    const double step = f / dg;
    u -= step;
    if (step <= 2e-16 * u) break;
  }
  return u;
}

double coulombSlipDuration(double q) {
  if (!(q > 0.0)) return 0.0;
  if (!(q <= 0.5 * kPi)) return coulombSlipDurationReference(q);  // NaN, inf included
  if (q < kTinyQ) return 3.0 * q;  // g(u) = u/3 + u^3/135 + ...: relative error below 1e-40
  const double u0 = q * slipDurationTable()(q * q);
  const SlipResidual r = slipResidual(u0, q);
  return u0 - r.f / r.dg;
}

}  // namespace metrosync
