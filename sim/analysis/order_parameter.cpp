#include "sim/analysis/order_parameter.h"

#include <cmath>
#include <complex>

namespace metrosync {

double pendulumPhase(double theta, double thetadot, double omega) {
  return std::atan2(theta * omega, thetadot);  // theta = A sin phi, thetadot / omega = A cos phi
}

Order orderParameter(const std::vector<double>& phases) {
  if (phases.empty()) return {};
  std::complex<double> z(0.0, 0.0);
  for (double phi : phases) z += std::polar(1.0, phi);
  z /= static_cast<double>(phases.size());
  Order o;
  o.r = std::abs(z);
  o.Phi = o.r > 0 ? std::arg(z) : 0.0;
  return o;
}

}  // namespace metrosync
