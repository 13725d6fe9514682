#include "sim/analysis/periodic_orbit/scaled_model.h"

#include <cmath>

namespace metrosync::orbit {

ScaledModel::ScaledModel(const Rig& rig)
    : eq_(rig),
      sp_(computeScaled(rig)),
      n_(eq_.numSwinging()),
      d_(2 * eq_.numSwinging() + 2),
      spring_(eq_.hasPlatform() && rig.platform.spring_N_m > 0),
      k_spring_(eq_.hasPlatform() ? rig.platform.spring_N_m : 0.0),
      omega0_(1.0 / sp_.time_scale_s),
      rows_scaled_(rig.units == Units::Scaled) {
  scale_.assign(d_, 1.0);
  scale_[kX] = sp_.x_scale_m;
  scale_[kV] = sp_.x_scale_m * omega0_;
  for (int j = 0; j < n_; ++j) {
    scale_[theta(j)] = sp_.angle_scale;
    scale_[omega(j)] = sp_.angle_scale * omega0_;
  }
}

std::vector<double> ScaledModel::physical(const Vec& z) const {
  std::vector<double> y(d_ + 2, 0.0);  // + the engine's two energy quadratures
  for (int k = 0; k < d_; ++k) y[k] = scale_[k] * z(k);
  return y;
}

Vec ScaledModel::deltaFromPhysical(const std::vector<double>& dy) const {
  Vec dz(d_);
  for (int k = 0; k < d_; ++k) dz(k) = dy[k] / scale_[k];
  return dz;
}

Vec ScaledModel::rhs(const Vec& z, PlatformMode mode) const {
  const std::vector<double> y = physical(z);
  std::vector<double> dy(d_ + 2, 0.0);
  eq_.rhs(y.data(), mode, dy.data());
  return deltaFromPhysical(dy) * sp_.time_scale_s;  // d/dt = (1 / omega0) d/dt-bar
}

ScaledModel::PlatformSums ScaledModel::platformSums(const std::vector<double>& y) const {
  PlatformSums p;
  p.dG = Vec::Zero(d_);
  p.dS = Vec::Zero(d_);
  p.G = -k_spring_ * y[kX];
  p.dG(kX) = -k_spring_;
  for (int j = 0; j < n_; ++j) {
    const direct::PendulumConstants& c = eq_.pendulum(j);
    const double s = std::sin(y[theta(j)]), co = std::cos(y[theta(j)]), w = y[omega(j)];
    const double cj = c.mL * co, r = -c.mgL * s - c.damping * w;
    p.G += c.mL * s * w * w - cj * r * c.inv_inertia;
    p.S += cj * cj * c.inv_inertia;
    // d/dtheta of mL s w^2 - c r / I with dc = -mL s, dr = -mgL co
    p.dG(theta(j)) = c.mL * co * w * w + (c.mL * s * r + cj * c.mgL * co) * c.inv_inertia;
    p.dG(omega(j)) = 2 * c.mL * s * w + cj * c.damping * c.inv_inertia;
    p.dS(theta(j)) = -2 * cj * c.mL * s * c.inv_inertia;
  }
  return p;
}

// e1.1a-c as MetronomeEquations::rhs writes them: Meff a = G + F, I_j w_j' = r_j - c_j a.
Mat ScaledModel::physicalJacobian(const std::vector<double>& y, PlatformMode mode) const {
  Mat J = Mat::Zero(d_, d_);
  const bool moving = eq_.hasPlatform() && !(coulomb() && mode == PlatformMode::Stuck);
  double a = 0.0;
  Vec da = Vec::Zero(d_);
  if (moving) {
    const PlatformSums p = platformSums(y);
    const double v = y[kV];
    const double F = eq_.friction().force(v, mode);
    const double meff = eq_.totalMass() - p.S;
    a = (p.G + F) / meff;
    da = (p.dG + a * p.dS) / meff;                        // d((G + F) / (M - S))
    da(kV) += eq_.friction().forceSlope(v, mode) / meff;  // the law's dF/dxdot
    J(kX, kV) = 1.0;
    J.row(kV) = da.transpose();
  }
  for (int j = 0; j < n_; ++j) {
    const direct::PendulumConstants& c = eq_.pendulum(j);
    const double s = std::sin(y[theta(j)]), co = std::cos(y[theta(j)]);
    J(theta(j), omega(j)) = 1.0;
    if (moving) J.row(omega(j)) = -c.mL * co * c.inv_inertia * da.transpose();
    // dr/dtheta - dc/dtheta a, dr/dw
    J(omega(j), theta(j)) += (-c.mgL * co + c.mL * s * a) * c.inv_inertia;
    J(omega(j), omega(j)) += -c.damping * c.inv_inertia;
  }
  return J;
}

Mat ScaledModel::toScaled(const Mat& jac_phys, double time_factor) const {
  Mat J = jac_phys;
  for (int k = 0; k < d_; ++k)
    for (int l = 0; l < d_; ++l) J(k, l) *= time_factor * scale_[l] / scale_[k];
  return J;
}

Mat ScaledModel::jacobian(const Vec& z, PlatformMode mode) const {
  return toScaled(physicalJacobian(physical(z), mode), sp_.time_scale_s);
}

double ScaledModel::holdingForce(const Vec& z) const {
  const std::vector<double> y = physical(z);
  return eq_.holdingForce(y.data());
}

Vec ScaledModel::holdingForceGradient(const Vec& z) const {
  const PlatformSums p = platformSums(physical(z));
  Vec g = -p.dG;  // H = -G
  for (int k = 0; k < d_; ++k) g(k) *= scale_[k];
  g(kV) = 0.0;
  return g;
}

PlatformMode ScaledModel::modeAtRest(const Vec& z) const {
  return eq_.dryFriction().modeAtRest(holdingForce(z));
}

Vec ScaledModel::tick(const Vec& z, const std::vector<int>& ticked) const {
  std::vector<double> y = physical(z), pins(n_, 0.0);
  for (int j : ticked) pins[j] = eq_.escapement(j).tickImpulse(y[theta(j)]);
  eq_.applyImpulse(y.data(), pins.data(), 0.0);
  return deltaFromPhysical(y);
}

// D of y + M(theta)^-1 p: the impulse is fixed, the mass matrix depends on the angles through
// c_j = m_j L_j cos theta_j. dv = -Q / Meff, Q = sum c_j p_j / I_j; dw_j = (p_j - c_j dv) / I_j.
Mat ScaledModel::tickJacobian(const Vec& z, const std::vector<int>& ticked) const {
  Mat D = Mat::Identity(d_, d_);
  if (!eq_.hasPlatform()) return D;  // dw_j = p_j / I_j: no dependence on the state
  const std::vector<double> y = physical(z);
  std::vector<double> p(n_, 0.0);
  for (int j : ticked) p[j] = eq_.escapement(j).tickImpulse(y[theta(j)]);
  const PlatformSums sums = platformSums(y);
  const double meff = eq_.totalMass() - sums.S;
  double Q = 0.0;
  for (int j = 0; j < n_; ++j)
    Q += eq_.pendulum(j).mL * std::cos(y[theta(j)]) * p[j] * eq_.pendulum(j).inv_inertia;
  const double dv = -Q / meff;
  Mat Dp = Mat::Zero(d_, d_);
  for (int k = 0; k < n_; ++k) {
    const direct::PendulumConstants& ck = eq_.pendulum(k);
    const double dQ = -ck.mL * std::sin(y[theta(k)]) * p[k] * ck.inv_inertia;
    const double ddv = (-dQ + dv * sums.dS(theta(k))) / meff;
    Dp(kV, theta(k)) = ddv;
    for (int j = 0; j < n_; ++j) {
      const direct::PendulumConstants& cj = eq_.pendulum(j);
      const double dc = j == k ? -cj.mL * std::sin(y[theta(j)]) : 0.0;
      Dp(omega(j), theta(k)) = -(dc * dv + cj.mL * std::cos(y[theta(j)]) * ddv) * cj.inv_inertia;
    }
  }
  return D + toScaled(Dp, 1.0);
}

Vec ScaledModel::plasticStop(const Vec& z) const {
  std::vector<double> y = physical(z);
  const std::vector<double> none(n_, 0.0);
  const double v = y[kV];
  if (v != 0) eq_.applyImpulse(y.data(), none.data(), -v / eq_.platformMobility(y.data()));
  Vec out = deltaFromPhysical(y);
  out(kV) = 0.0;  // held: the resolver's setMode(Stuck)
  return out;
}

// dv = -v (the impulse -v Meff on x), dw_j = c_j v / I_j.
Mat ScaledModel::plasticStopJacobian(const Vec& z) const {
  const std::vector<double> y = physical(z);
  Mat Dp = Mat::Identity(d_, d_);
  Dp(kV, kV) = 0.0;
  for (int j = 0; j < n_; ++j) {
    const direct::PendulumConstants& c = eq_.pendulum(j);
    Dp(omega(j), kV) = c.mL * std::cos(y[theta(j)]) * c.inv_inertia;
    Dp(omega(j), theta(j)) += -c.mL * std::sin(y[theta(j)]) * y[kV] * c.inv_inertia;
  }
  return toScaled(Dp, 1.0);
}

Vec ScaledModel::stateFromRow(const std::vector<double>& row) const {
  // a scaled rig's rows are in scaled units already; a physical rig's in SI
  auto value = [&](int k, double v) { return rows_scaled_ ? v : v / scale_[k]; };
  Vec z(d_);
  z(kX) = value(kX, row[1]);
  z(kV) = value(kV, row[2]);
  for (int j = 0; j < n_; ++j) {
    const int i = rigIndex(j);
    z(theta(j)) = value(theta(j), row[3 + 2 * i]);
    z(omega(j)) = value(omega(j), row[4 + 2 * i]);
  }
  return z;
}

double ScaledModel::timeFromRow(const std::vector<double>& row) const {
  return rows_scaled_ ? row[0] : row[0] * omega0_;
}

void ScaledModel::setStart(Rig& rig, const Vec& z) const {
  const std::vector<double> y = physical(z);
  if (eq_.hasPlatform()) {
    rig.platform.start_x_m = y[kX];
    rig.platform.start_v_m_s = y[kV];
  }
  for (int j = 0; j < n_; ++j) {
    MetronomeSpec& m = rig.metronomes[rigIndex(j)];
    m.start_angle_rad = y[theta(j)];
    m.start_rate_rad_s = y[omega(j)];
  }
}

}  // namespace metrosync::orbit
