// The full model (models/platform_arrow.h, e1.1a-c) in the paper's scaled variables (s2.1),
// with the derivatives a periodic orbit's linearization needs: the Jacobian of the right-hand side
// in each platform mode, the gradient of the holding force, and the Jacobians of the two jump
// maps the event resolver applies (a tick's impulse through the mass matrix, a plastic stop).
// The model in physical units with its derivatives (physical_model.h), seen through the scales:
// z = y / scale, t = omega0 t-bar, so that a Jacobian is D^-1 J D (D = diag(scale)) times the time
// factor where it is a rate.
//
// State z, (d x 1), d = 2n + 2, scaled: x, xdot, theta_1..theta_n, thetadot_1..thetadot_n (the n
// swinging pendulums in rig order; the engine's layout without its two energy quadratures).
// Scaled time t = omega0 t-bar. Physical = scale * scaled (models/scaling.h).
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "models/rig.h"
#include "models/scaling.h"
#include "sim/analysis/periodic_orbit/physical_model.h"

namespace metrosync::orbit {

class ScaledModel {
 public:
  explicit ScaledModel(const Rig& rig);

  int n() const { return n_; }    // swinging pendulums
  int dim() const { return d_; }  // 2n + 2
  static constexpr int kX = 0, kV = 1;
  int theta(int j) const { return 2 + j; }
  int omega(int j) const { return 2 + n_ + j; }
  bool hasPlatform() const { return pm_.hasPlatform(); }
  bool coulomb() const { return pm_.coulomb(); }
  bool hasSpring() const { return spring_; }
  int rigIndex(int j) const { return pm_.rigIndex(j); }
  double thetaC(int j) const { return pm_.equations().pendulum(j).theta_c / sp_.angle_scale; }
  bool ticks(int j) const { return pm_.equations().pendulum(j).impulse > 0; }
  const ScaledParams& scaled() const { return sp_; }
  // the same model in physical units, and the conversions of a state
  const PhysicalModel& physicalModel() const { return pm_; }
  Vec toPhysical(const Vec& z) const;
  Vec fromPhysical(const Vec& y) const;
  // a physical state's Jacobian as the scaled state's (D^-1 J D)
  Mat scaledJacobian(const Mat& jac_physical) const;

  // dz/dt in `mode` (Coulomb: stuck holds x and xdot; other laws ignore the mode).
  Vec rhs(const Vec& z, PlatformMode mode) const;
  // d(rhs)/dz, (d x d).
  Mat jacobian(const Vec& z, PlatformMode mode) const;

  // The force friction must supply to hold the platform still (physical units: only its sign
  // and the direction of its gradient matter here), and its gradient in z (xdot's entry 0).
  double holdingForce(const Vec& z) const;
  Vec holdingForceGradient(const Vec& z) const;
  // The Coulomb law's mode of a platform at rest at z (stuck unless it breaks free).
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
  PhysicalModel pm_;
  ScaledParams sp_;
  int n_ = 0, d_ = 0;
  bool spring_ = false;
  Vec scale_;  // (d x 1): physical = scale_ * scaled, per component
  double omega0_ = 1.0;
  bool rows_scaled_ = false;  // the engine's rows are in scaled units (a scaled rig)
};

}  // namespace metrosync::orbit
