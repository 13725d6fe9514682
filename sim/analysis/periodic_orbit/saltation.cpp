#include "sim/analysis/periodic_orbit/saltation.h"

#include <cmath>

namespace metrosync::orbit {

namespace {

// The engine stopped the platform at once after the ticks (a micro-slip, resolver.cpp): its
// velocity after the window is the rounding of the stop, far below the ticks' jump.
constexpr double kStoppedFraction = 1e-9;

Mat saltationOf(const Mat& Dg, const Vec& f_minus, const Vec& f_plus, const Vec& dh) {
  return Dg + (f_plus - Dg * f_minus) * dh.transpose() / dh.dot(f_minus);
}

PlatformMode slipWay(double v, PlatformMode otherwise) {
  return v > 0 ? PlatformMode::SlipPositive : (v < 0 ? PlatformMode::SlipNegative : otherwise);
}

struct Jumped {
  Vec z;
  Mat S;
};

// The ticks of the window one after the other (index order), each with its own event function.
Jumped tickWindow(const ScaledModel& m, const EngineWindow& w) {
  const int d = m.dim();
  Jumped out{w.before, Mat::Identity(d, d)};
  PlatformMode mode = w.mode_before;
  for (size_t i = 0; i < w.ticked.size(); ++i) {
    const int j = w.ticked[i];
    const Vec& z = out.z;
    Vec dh = Vec::Zero(d);
    dh(m.theta(j)) = z(m.theta(j)) > 0 ? 1.0 : -1.0;
    const Vec f_minus = m.rhs(z, mode);
    Mat Dg = m.tickJacobian(z, {j});
    Vec zp = m.tick(z, {j});
    PlatformMode mp = m.coulomb() ? slipWay(zp(ScaledModel::kV), mode) : mode;
    if (i + 1 == w.ticked.size()) {
      // a platform held after the window (cancelling ticks, or a micro-slip the engine stopped
      // at once): a perturbation's velocity is stopped by friction at once as well
      const double v_tick = zp(ScaledModel::kV), v_after = w.after(ScaledModel::kV);
      const bool stopped = v_tick != 0 && std::abs(v_after) <= kStoppedFraction * std::abs(v_tick);
      if (m.coulomb() && (stopped || w.mode_after == PlatformMode::Stuck)) {
        Dg = m.plasticStopJacobian(zp) * Dg;
        zp = m.plasticStop(zp);
      }
      mp = w.mode_after;
    }
    out.S = saltationOf(Dg, f_minus, m.rhs(zp, mp), dh) * out.S;
    out.z = zp;
    mode = mp;
  }
  return out;
}

// A platform switch alone: the slip stops (or reverses) at xdot = 0, or the stuck platform breaks
// free where |H| reaches the bound; the state does not jump.
Jumped platformWindow(const ScaledModel& m, const EngineWindow& w) {
  const int d = m.dim();
  Vec dh = Vec::Zero(d);
  if (w.mode_before == PlatformMode::Stuck) {
    const double H = m.holdingForce(w.before);
    dh = (H >= 0 ? 1.0 : -1.0) * m.holdingForceGradient(w.before);
  } else {
    dh(ScaledModel::kV) = -static_cast<int>(w.mode_before);
  }
  Vec z = w.before;
  if (w.mode_after == PlatformMode::Stuck) z(ScaledModel::kV) = 0.0;
  const Mat I = Mat::Identity(d, d);
  return {z, saltationOf(I, m.rhs(w.before, w.mode_before), m.rhs(z, w.mode_after), dh)};
}

}  // namespace

Mat saltation(const ScaledModel& model, const EngineWindow& window) {
  return window.ticked.empty() ? platformWindow(model, window).S : tickWindow(model, window).S;
}

Vec jumpedState(const ScaledModel& model, const EngineWindow& window) {
  return window.ticked.empty() ? platformWindow(model, window).z : tickWindow(model, window).z;
}

}  // namespace metrosync::orbit
