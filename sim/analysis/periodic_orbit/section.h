// The Poincare section of a locked state and its coordinates: swinging pendulum r crossing
// theta_r = 0 upwards. On it the state is given by u, in scaled variables:
//   [x (only with a platform spring: otherwise x is cyclic, the equations do not see it)]
//   [xdot (a platform that can move)]  theta_j (j != r)  thetadot_j (every j)
// so a locked state is a fixed point of the return map u -> P(u), dim u = 2n (+ 1 with a spring,
// - 1 on a fixed platform), and the multipliers of P are the orbit's nontrivial Floquet
// multipliers (the trivial 1 along the flow is the section's; x's neutral 1 is left out).
#pragma once

#include <string>
#include <vector>

#include "sim/analysis/periodic_orbit/scaled_model.h"

namespace metrosync::orbit {

class Section {
 public:
  Section(const ScaledModel& model, int pendulum);

  int pendulum() const { return r_; }
  int dim() const { return static_cast<int>(index_.size()); }
  // z on the section from u (theta_r = 0, x = 0 without a spring); a platform velocity within
  // kRestVelocity of 0 is exactly 0, so that the engine decides its mode at rest.
  Vec stateOf(const Vec& u) const;
  Vec coordinatesOf(const Vec& z) const;
  // The return map's Jacobian from the sensitivity phi = dz(T)/dz(0) at the return (z1, f1 the
  // vector field there): phi corrected for the return time, rows and columns of u.
  Mat reduce(const Mat& phi, const Vec& f1) const;
  // The z component of each coordinate, and its name ("xdot", "theta_2", "thetadot_1"; 1-based
  // rig numbers).
  int component(int k) const { return index_[k]; }
  std::string name(int k) const;

  // A platform velocity below this (scaled) on the section is rest: far below the Newton
  // tolerance of the orbit (1e-10) and far above the rounding of a stuck platform's zero.
  static constexpr double kRestVelocity = 1e-13;

 private:
  const ScaledModel& model_;
  int r_;
  std::vector<int> index_;
};

}  // namespace metrosync::orbit
