#include "sim/analysis/linear_decay.h"

#include <cmath>

#include "base/constants.h"

namespace metrosync {

bool isSection3ARig(const Rig& rig) {
  if (rig.units != Units::Physical || rig.metronomes.empty()) return false;
  for (const auto& m : rig.metronomes)
    if (!m.locked) return false;
  return rig.platform.spring_N_m > 0 && rig.platform.friction.coulombCoefficient().has_value();
}

void LinearDecay::addExtreme(double t_s, double x_m) {
  t_.push_back(t_s);
  a_.push_back(std::abs(x_m));
}

std::optional<Section3AResult> LinearDecay::result(const Rig& rig) const {
  const size_t n = t_.size();
  if (n < 3 || rig.platform.spring_N_m <= 0) return std::nullopt;
  double st = 0, sa = 0;
  for (size_t k = 0; k < n; ++k) st += t_[k], sa += a_[k];
  const double tm = st / n, am = sa / n;
  double stt = 0, sta = 0;
  for (size_t k = 0; k < n; ++k) {
    stt += (t_[k] - tm) * (t_[k] - tm);
    sta += (t_[k] - tm) * (a_[k] - am);
  }
  if (stt <= 0) return std::nullopt;
  Section3AResult r;
  r.slope_m_s = -sta / stt;  // the amplitude decreases: a positive decay rate
  r.period_s = 2 * kPi * std::sqrt(rig.totalMass() / rig.platform.spring_N_m);
  r.mu_bar = r.slope_m_s * kPi * kPi / (r.period_s * rig.gravity_m_s2);
  r.extremes = static_cast<int>(n);
  return r;
}

}  // namespace metrosync
