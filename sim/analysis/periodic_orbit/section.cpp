#include "sim/analysis/periodic_orbit/section.h"

#include <cmath>

namespace metrosync::orbit {

Section::Section(const ScaledModel& model, int pendulum) : model_(model), r_(pendulum) {
  if (model.hasSpring()) index_.push_back(ScaledModel::kX);
  if (model.hasPlatform()) index_.push_back(ScaledModel::kV);
  for (int j = 0; j < model.n(); ++j)
    if (j != r_) index_.push_back(model.theta(j));
  for (int j = 0; j < model.n(); ++j) index_.push_back(model.omega(j));
}

Vec Section::stateOf(const Vec& u) const {
  Vec z = Vec::Zero(model_.dim());
  for (int k = 0; k < dim(); ++k) z(index_[k]) = u(k);
  if (std::abs(z(ScaledModel::kV)) < kRestVelocity) z(ScaledModel::kV) = 0.0;
  return z;
}

Vec Section::coordinatesOf(const Vec& z) const {
  Vec u(dim());
  for (int k = 0; k < dim(); ++k) u(k) = z(index_[k]);
  return u;
}

Mat Section::reduce(const Mat& phi, const Vec& f1) const {
  // a perturbation that moves the return along the flow is taken back to the section:
  // (I - f1 e_r^T / f1_r) phi, e_r the gradient of theta_r
  const int r = model_.theta(r_);
  const Mat onto = phi - f1 * phi.row(r) / f1(r);
  Mat out(dim(), dim());
  for (int k = 0; k < dim(); ++k)
    for (int l = 0; l < dim(); ++l) out(k, l) = onto(index_[k], index_[l]);
  return out;
}

std::string Section::name(int k) const {
  const int c = index_[k];
  if (c == ScaledModel::kX) return "x";
  if (c == ScaledModel::kV) return "xdot";
  for (int j = 0; j < model_.n(); ++j) {
    const std::string num = std::to_string(model_.rigIndex(j) + 1);
    if (c == model_.theta(j)) return "theta_" + num;
    if (c == model_.omega(j)) return "thetadot_" + num;
  }
  return "?";
}

}  // namespace metrosync::orbit
