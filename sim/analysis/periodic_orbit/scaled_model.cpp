#include "sim/analysis/periodic_orbit/scaled_model.h"

#include <cmath>

namespace metrosync::orbit {

ScaledModel::ScaledModel(const Rig& rig)
    : pm_(rig),
      sp_(computeScaled(rig)),
      n_(pm_.n()),
      d_(pm_.dim()),
      spring_(pm_.hasPlatform() && rig.platform.spring_N_m > 0),
      omega0_(1.0 / sp_.time_scale_s),
      rows_scaled_(rig.units == Units::Scaled) {
  scale_ = Vec::Ones(d_);
  scale_(kX) = sp_.x_scale_m;
  scale_(kV) = sp_.x_scale_m * omega0_;
  for (int j = 0; j < n_; ++j) {
    scale_(theta(j)) = sp_.angle_scale;
    scale_(omega(j)) = sp_.angle_scale * omega0_;
  }
}

Vec ScaledModel::toPhysical(const Vec& z) const {
  return scale_.cwiseProduct(z);
}

Vec ScaledModel::fromPhysical(const Vec& y) const {
  return y.cwiseQuotient(scale_);
}

Mat ScaledModel::scaledJacobian(const Mat& jac_physical) const {
  return scale_.cwiseInverse().asDiagonal() * jac_physical * scale_.asDiagonal();
}

Vec ScaledModel::rhs(const Vec& z, PlatformMode mode) const {
  return fromPhysical(pm_.rhs(toPhysical(z), mode)) * sp_.time_scale_s;  // d/dt = d/dt-bar / omega0
}

Mat ScaledModel::jacobian(const Vec& z, PlatformMode mode) const {
  return scaledJacobian(pm_.jacobian(toPhysical(z), mode)) * sp_.time_scale_s;
}

double ScaledModel::holdingForce(const Vec& z) const {
  return pm_.holdingForce(toPhysical(z));
}

Vec ScaledModel::holdingForceGradient(const Vec& z) const {
  return pm_.holdingForceGradient(toPhysical(z)).cwiseProduct(scale_);  // d/dz = scale d/dy
}

PlatformMode ScaledModel::modeAtRest(const Vec& z) const {
  return pm_.modeAtRest(toPhysical(z));
}

Vec ScaledModel::tick(const Vec& z, const std::vector<int>& ticked) const {
  return fromPhysical(pm_.tick(toPhysical(z), ticked));
}

Mat ScaledModel::tickJacobian(const Vec& z, const std::vector<int>& ticked) const {
  return scaledJacobian(pm_.tickJacobian(toPhysical(z), ticked));
}

Vec ScaledModel::plasticStop(const Vec& z) const {
  return fromPhysical(pm_.plasticStop(toPhysical(z)));
}

Mat ScaledModel::plasticStopJacobian(const Vec& z) const {
  return scaledJacobian(pm_.plasticStopJacobian(toPhysical(z)));
}

Vec ScaledModel::stateFromRow(const std::vector<double>& row) const {
  // a scaled rig's rows are in scaled units already; a physical rig's in SI
  const Vec y = pm_.stateFromRow(row);
  return rows_scaled_ ? y : fromPhysical(y);
}

double ScaledModel::timeFromRow(const std::vector<double>& row) const {
  return rows_scaled_ ? row[0] : row[0] * omega0_;
}

void ScaledModel::setStart(Rig& rig, const Vec& z) const {
  const Vec y = toPhysical(z);
  if (pm_.hasPlatform()) {
    rig.platform.start_x_m = y(kX);
    rig.platform.start_v_m_s = y(kV);
  }
  for (int j = 0; j < n_; ++j) {
    MetronomeSpec& m = rig.metronomes[rigIndex(j)];
    m.start_angle_rad = y(theta(j));
    m.start_rate_rad_s = y(omega(j));
  }
}

}  // namespace metrosync::orbit
