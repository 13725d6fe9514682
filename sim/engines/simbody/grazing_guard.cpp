#include "sim/engines/simbody/grazing_guard.h"

#include <cmath>

namespace metrosync {

double hermiteInteriorExtreme(double p0, double d0, double p1, double d1, double h, bool want_max) {
  const double a = 6 * p0 + 3 * h * d0 - 6 * p1 + 3 * h * d1;
  const double b = -6 * p0 - 4 * h * d0 + 6 * p1 - 2 * h * d1;
  const double c = h * d0;
  auto eval = [&](double s) {
    const double s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * h * d0 + (-2 * s3 + 3 * s2) * p1 +
           (s3 - s2) * h * d1;
  };
  double best = std::nan("");
  auto consider = [&](double s) {
    if (!(s > 0 && s < 1)) return;
    const double v = eval(s);
    if (std::isnan(best) || (want_max ? v > best : v < best)) best = v;
  };
  if (std::abs(a) < 1e-300) {
    if (std::abs(b) > 1e-300) consider(-c / b);
  } else {
    const double disc = b * b - 4 * a * c;
    if (disc >= 0) {
      const double r = std::sqrt(disc);
      consider((-b + r) / (2 * a));
      consider((-b - r) / (2 * a));
    }
  }
  return best;
}

bool tickGrazed(const StepEnd& a, const StepEnd& b, int j, const Escapement& esc) {
  const double h = b.t - a.t;
  if (a.w[j] * b.w[j] >= 0) return false;  // no turning point inside the step
  const double tc = esc.theta_c;
  const bool at_max = a.w[j] > 0;  // turning at a maximum of theta
  const double side = at_max ? 1.0 : -1.0;
  // both ends inside the critical angle on this side: a double crossing would be invisible
  if (side * a.th[j] >= tc || side * b.th[j] >= tc) return false;
  const double ext = side * hermiteInteriorExtreme(a.th[j], a.w[j], b.th[j], b.w[j], h, at_max);
  // margin: well above the cubic's own error (the rates at the ends are O(h) near a turn)
  const double margin = 1e-6 * tc + 1e-3 * h * (std::abs(a.w[j]) + std::abs(b.w[j]));
  return ext > tc - margin;
}

bool slipGrazed(const StepEnd& a, const StepEnd& b, int p, PlatformMode mode, bool event_step) {
  const double h = b.t - a.t;
  const double sgn = static_cast<int>(mode);
  if (sgn * b.v[p] < 0 && !event_step) return true;
  if (sgn * a.v[p] > 0 && sgn * b.v[p] > 0) {
    // a dip of the speed inside the step (not the monotone approach to a stop, which the
    // witness sees) that comes close to zero
    const double low = sgn * hermiteInteriorExtreme(a.v[p], a.a[p], b.v[p], b.a[p], h, sgn < 0);
    const double margin = 1e-3 * h * std::abs(a.a[p] - b.a[p]);
    if (low < margin) return true;
  }
  return false;
}

}  // namespace metrosync
