// The full model (models/minimal_equations.h, e1.1a-c) in the paper's scaled variables (s2.1),
// with the derivatives a periodic orbit's linearization needs: the Jacobian of the right-hand side
// in each platform mode, the gradient of the holding force, and the Jacobians of the two jump
// maps the event resolver applies (a tick's impulse through the mass matrix, a plastic stop).
// The engine's equations are evaluated as they are (MetronomeEquations); only their derivatives
// are written here, in closed form, and checked against differences in the tests.
//
// State z, (d x 1), d = 2n + 2, scaled: x, xdot, theta_1..theta_n, thetadot_1..thetadot_n (the n
// swinging pendulums in rig order; the engine's layout without its two energy quadratures).
// Scaled time t = omega0 t-bar. Physical = scale * scaled (models/scaling.h).
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "models/minimal_equations.h"
#include "models/rig.h"
#include "models/scaling.h"

namespace metrosync::orbit {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

class ScaledModel {
 public:
  explicit ScaledModel(const Rig& rig);

  int n() const { return n_; }    // swinging pendulums
  int dim() const { return d_; }  // 2n + 2
  static constexpr int kX = 0, kV = 1;
  int theta(int j) const { return 2 + j; }
  int omega(int j) const { return 2 + n_ + j; }
  bool hasPlatform() const { return eq_.hasPlatform(); }
  // the law has stick and slip (a set-valued law: Coulomb's, Stribeck's)
  bool coulomb() const { return eq_.friction().setValued(); }
  bool hasSpring() const { return spring_; }
  int rigIndex(int j) const { return eq_.pendulum(j).rig_index; }
  double thetaC(int j) const { return eq_.pendulum(j).theta_c / sp_.angle_scale; }
  bool ticks(int j) const { return eq_.pendulum(j).impulse > 0; }
  const ScaledParams& scaled() const { return sp_; }

  // dz/dt in `mode` (a set-valued law: stuck holds x and xdot; other laws ignore the mode).
  Vec rhs(const Vec& z, PlatformMode mode) const;
  // d(rhs)/dz, (d x d).
  Mat jacobian(const Vec& z, PlatformMode mode) const;

  // The force friction must supply to hold the platform still (physical units: only its sign
  // and the direction of its gradient matter here), and its gradient in z (xdot's entry 0).
  double holdingForce(const Vec& z) const;
  Vec holdingForceGradient(const Vec& z) const;
  // The set-valued law's mode of a platform at rest at z (stuck unless it breaks free).
  PlatformMode modeAtRest(const Vec& z) const;

  // A combined tick: side_j * J-bar_j on the pins of `ticked` (side by the sign of theta_j),
  // through the mass matrix with the platform free (a fixed platform takes none): the state after
  // it, and the jump map's Jacobian at z.
  Vec tick(const Vec& z, const std::vector<int>& ticked) const;
  Mat tickJacobian(const Vec& z, const std::vector<int>& ticked) const;
  // A plastic stop: friction's impulse on x alone brings xdot to 0, the pendulums take the
  // reaction (sim/events/resolver.cpp stopAndSettle); the state after it and its Jacobian.
  Vec plasticStop(const Vec& z) const;
  Mat plasticStopJacobian(const Vec& z) const;

  // Conversions: an engine row (t, x, xdot, theta_i, thetadot_i for every rig metronome,
  // platform; in the rig's units) to the scaled state and time; the scaled state into the rig's
  // start (physical).
  Vec stateFromRow(const std::vector<double>& row) const;
  double timeFromRow(const std::vector<double>& row) const;
  void setStart(Rig& rig, const Vec& z) const;
  // Scaled time -> seconds.
  double seconds(double t) const { return t * sp_.time_scale_s; }

 private:
  // physical <-> scaled, per component of z: physical = scale_[k] * scaled
  std::vector<double> physical(const Vec& z) const;
  Mat physicalJacobian(const std::vector<double>& y, PlatformMode mode) const;
  // the platform's sums at y: G (all forces on x but friction), S = sum c_j^2 / I_j and their
  // gradients in y (d x 1)
  struct PlatformSums {
    double G = 0.0, S = 0.0;
    Vec dG, dS;
  };
  PlatformSums platformSums(const std::vector<double>& y) const;
  Mat toScaled(const Mat& jac_phys, double time_factor) const;
  Vec deltaFromPhysical(const std::vector<double>& dy) const;

  direct::MetronomeEquations eq_;
  ScaledParams sp_;
  int n_ = 0, d_ = 0;
  bool spring_ = false;
  double k_spring_ = 0.0;      // N/m
  std::vector<double> scale_;  // (d x 1)
  double omega0_ = 1.0;
  bool rows_scaled_ = false;  // the engine's rows are in scaled units (a scaled rig)
};

}  // namespace metrosync::orbit
