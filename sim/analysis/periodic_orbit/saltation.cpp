#include "sim/analysis/periodic_orbit/saltation.h"

#include <cmath>

namespace metrosync::orbit {

namespace {

// The engine stopped the platform at once after the ticks (a micro-slip, resolver.cpp): its
// velocity after the window is the rounding of the stop, far below the ticks' jump.
constexpr double kStoppedFraction = 1e-9;

// S = Dg + (f+ - Dg f-) dh^T / (dh . f-), and with the parameters' h_p and Dg_p (when Dg_p is not
// empty) Sp = Dg_p + (f+ - Dg f-) h_p^T / (dh . f-).
struct Saltation {
  Mat S, Sp;
};
Saltation saltationOf(const Mat& Dg, const Mat& Dg_p, const Vec& f_minus, const Vec& f_plus,
                      const Vec& dh, const Vec& h_p) {
  const Vec kick = (f_plus - Dg * f_minus) / dh.dot(f_minus);
  Saltation s{Dg + kick * dh.transpose(), Mat()};
  if (Dg_p.size() > 0) s.Sp = Dg_p + kick * h_p.transpose();
  return s;
}

PlatformMode slipWay(double v, PlatformMode otherwise) {
  return v > 0 ? PlatformMode::SlipPositive : (v < 0 ? PlatformMode::SlipNegative : otherwise);
}

// The ticks of the window one after the other (index order), each with its own event function
// side theta_j - theta_c,j (so h_p = -1 at theta_c,j).
WindowJump tickWindow(const PhysicalModel& m, const EngineWindow& w, bool params) {
  const int d = m.dim(), P = m.parameterLayout().size();
  WindowJump out{w.before, Mat::Identity(d, d), params ? Mat::Zero(d, P) : Mat()};
  PlatformMode mode = w.mode_before;
  for (size_t i = 0; i < w.ticked.size(); ++i) {
    const int j = w.ticked[i];
    const Vec& y = out.after;
    Vec dh = Vec::Zero(d), h_p = Vec::Zero(P);
    dh(m.theta(j)) = y(m.theta(j)) > 0 ? 1.0 : -1.0;
    h_p(m.parameterLayout().thetaC(j)) = -1.0;
    const Vec f_minus = m.rhs(y, mode);
    Mat Dg = m.tickJacobian(y, {j});
    Mat Dg_p = params ? m.tickParameterJacobian(y, {j}) : Mat();
    Vec yp = m.tick(y, {j});
    PlatformMode mp = m.coulomb() ? slipWay(yp(PhysicalModel::kV), mode) : mode;
    if (i + 1 == w.ticked.size()) {
      // a platform held after the window (cancelling ticks, or a micro-slip the engine stopped
      // at once): a perturbation's velocity is stopped by friction at once as well
      const double v_tick = yp(PhysicalModel::kV), v_after = w.after(PhysicalModel::kV);
      const bool stopped = v_tick != 0 && std::abs(v_after) <= kStoppedFraction * std::abs(v_tick);
      if (m.coulomb() && (stopped || w.mode_after == PlatformMode::Stuck)) {
        const Mat stop = m.plasticStopJacobian(yp);
        if (params) Dg_p = stop * Dg_p + m.plasticStopParameterJacobian(yp);
        Dg = stop * Dg;
        yp = m.plasticStop(yp);
      }
      mp = w.mode_after;
    }
    const Saltation s = saltationOf(Dg, Dg_p, f_minus, m.rhs(yp, mp), dh, h_p);
    if (params) out.Sp = s.S * out.Sp + s.Sp;
    out.S = s.S * out.S;
    out.after = yp;
    mode = mp;
  }
  return out;
}

// A platform switch alone: the slip stops (or reverses) at xdot = 0, or the stuck platform breaks
// free where |H| reaches the static bound (h_p = sign(H) dH/dp - d(bound)/dp); the state does not
// jump.
WindowJump platformWindow(const PhysicalModel& m, const EngineWindow& w, bool params) {
  const int d = m.dim(), P = m.parameterLayout().size();
  Vec dh = Vec::Zero(d), h_p = Vec::Zero(P);
  if (w.mode_before == PlatformMode::Stuck) {
    const double side = m.holdingForce(w.before) >= 0 ? 1.0 : -1.0;
    dh = side * m.holdingForceGradient(w.before);
    if (params) h_p = side * m.holdingForceParameters(w.before) - m.staticBoundParameters();
  } else {
    dh(PhysicalModel::kV) = -static_cast<int>(w.mode_before);
  }
  Vec y = w.before;
  if (w.mode_after == PlatformMode::Stuck) y(PhysicalModel::kV) = 0.0;
  const Saltation s = saltationOf(Mat::Identity(d, d), params ? Mat::Zero(d, P) : Mat(),
                                  m.rhs(w.before, w.mode_before), m.rhs(y, w.mode_after), dh, h_p);
  return {y, s.S, s.Sp};
}

// the scaled window in physical units
EngineWindow physicalWindow(const ScaledModel& m, const EngineWindow& w) {
  EngineWindow p = w;
  p.before = m.toPhysical(w.before);
  p.after = m.toPhysical(w.after);
  return p;
}

}  // namespace

WindowJump windowJump(const PhysicalModel& model, const EngineWindow& window,
                      bool with_parameters) {
  return window.ticked.empty() ? platformWindow(model, window, with_parameters)
                               : tickWindow(model, window, with_parameters);
}

Mat saltation(const ScaledModel& model, const EngineWindow& window) {
  return model.scaledJacobian(
      windowJump(model.physicalModel(), physicalWindow(model, window), false).S);
}

Vec jumpedState(const ScaledModel& model, const EngineWindow& window) {
  return model.fromPhysical(
      windowJump(model.physicalModel(), physicalWindow(model, window), false).after);
}

}  // namespace metrosync::orbit
