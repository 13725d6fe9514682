// The full model (models/network_equations.h for a single board, e1.1a-c) in physical units, with
// the derivatives a linearization needs, in the state and in the rig's parameters:
//   the right-hand side's Jacobian in each platform mode, and its derivative in the parameters;
//   the holding force's gradient (the stick -> slip event) and the static bound's parameters;
//   the jump maps -- a tick's impulse through M(theta)^-1, a plastic stop -- with their Jacobians
//   in the state and in the parameters (an impulse's size, the masses it goes through).
// The equations are evaluated as NetworkEquations writes a single board's; only their derivatives
// are written here, in closed form, and checked against differences in tests/periodic_orbit. What
// depends on the friction law comes from the law (contact/friction_partials.h). ScaledModel
// (scaled_model.h) is this model in the paper's scaled variables.
//
// State y, (d x 1), d = 2n + 2, SI: x, xdot, theta_1..theta_n, thetadot_1..thetadot_n (the n
// swinging pendulums in rig order; the engine's layout without its two energy quadratures).
// Parameters p, (P x 1): the constants the equations are written in (ParameterLayout), so that a
// rig key's effect on the model is the direction dp/dkey (sim/analysis/fit/key_directions.h).
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "contact/friction_partials.h"
#include "models/network_equations.h"
#include "models/rig.h"

namespace metrosync::orbit {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

// Where each constant sits in p: per swinging pendulum j its m_j L_j, m_j g L_j, I_j, pivot
// damping nu-bar_j L_j^2, theta_c,j and J-bar_j; the platform's total mass M (everything on it),
// its spring k, the friction law's normal force N = M g and the law's values
// (FrictionLaw::values()); the start state y(0), (d x 1).
struct ParameterLayout {
  int n = 0, law_values = 0;
  static constexpr int kPerPendulum = 6;
  int mL(int j) const { return kPerPendulum * j; }
  int mgL(int j) const { return kPerPendulum * j + 1; }
  int inertia(int j) const { return kPerPendulum * j + 2; }
  int damping(int j) const { return kPerPendulum * j + 3; }
  int thetaC(int j) const { return kPerPendulum * j + 4; }
  int impulse(int j) const { return kPerPendulum * j + 5; }
  int mass() const { return kPerPendulum * n; }
  int spring() const { return mass() + 1; }
  int normalForce() const { return mass() + 2; }
  int lawValue(int i) const { return mass() + 3 + i; }
  int start(int k) const { return mass() + 3 + law_values + k; }  // of state component k
  int size() const { return start(2 * n + 2); }
};

class PhysicalModel {
 public:
  explicit PhysicalModel(const Rig& rig);

  int n() const { return n_; }    // swinging pendulums
  int dim() const { return d_; }  // 2n + 2
  static constexpr int kX = 0, kV = 1;
  int theta(int j) const { return 2 + j; }
  int omega(int j) const { return 2 + n_ + j; }
  bool hasPlatform() const { return eq_.hasPlatform(); }
  bool coulomb() const { return eq_.friction().setValued(); }
  int rigIndex(int j) const { return eq_.pendulum(j).rig_index; }
  const network::NetworkEquations& equations() const { return eq_; }
  const FrictionLaw& law() const { return law_; }
  // Does the friction law give its partials (contact/friction_partials.h)? Without them the
  // parameter derivatives are not available (the state's still are).
  bool hasParameterDerivatives() const { return law_partials_; }

  // The parameters and the start state of `rig` in this model's layout.
  const ParameterLayout& parameterLayout() const { return pl_; }
  Vec parameters() const { return p_; }
  Vec startState() const { return p_.tail(d_); }

  // dy/dt in `mode` (Coulomb: stuck holds x and xdot; other laws ignore the mode).
  Vec rhs(const Vec& y, PlatformMode mode) const;
  // d(rhs)/dy (d x d) and d(rhs)/dp (d x P).
  Mat jacobian(const Vec& y, PlatformMode mode) const;
  Mat parameterJacobian(const Vec& y, PlatformMode mode) const;
  // The variational equations of y's derivatives Y = dy/dq in k directions q of the parameters,
  // dp/dq = dirs: dY/dt = jacobian Y + parameterJacobian dirs (d x k), into dY, written without
  // forming either matrix. Y, dirs and dY column-major; dirs may be null (no parameter
  // direction: the state's Jacobian alone, as for a monodromy matrix).
  void variationalRates(const double* y, PlatformMode mode, const double* Y, const double* dirs,
                        int k, double* dY) const;

  // The force friction must supply to hold the platform still (N), its gradient in y (xdot's
  // entry 0) and in p.
  double holdingForce(const Vec& y) const;
  Vec holdingForceGradient(const Vec& y) const;
  Vec holdingForceParameters(const Vec& y) const;
  // The static bound's derivative in p (the largest holding force; a set-valued law only).
  Vec staticBoundParameters() const;
  // The Coulomb law's mode of a platform at rest at y (stuck unless it breaks free).
  PlatformMode modeAtRest(const Vec& y) const;

  // A combined tick: side_j * J-bar_j on the pins of `ticked` (side by the sign of theta_j),
  // through the mass matrix with the platform free (a fixed platform takes none): the state after
  // it, the jump map's Jacobian in y at y and in p (d x P).
  Vec tick(const Vec& y, const std::vector<int>& ticked) const;
  Mat tickJacobian(const Vec& y, const std::vector<int>& ticked) const;
  Mat tickParameterJacobian(const Vec& y, const std::vector<int>& ticked) const;
  // A plastic stop: friction's impulse on x alone brings xdot to 0, the pendulums take the
  // reaction (sim/events/resolver.cpp stopAndSettle); the state after it and its Jacobians.
  Vec plasticStop(const Vec& y) const;
  Mat plasticStopJacobian(const Vec& y) const;
  Mat plasticStopParameterJacobian(const Vec& y) const;

  // An engine row (t, x, xdot, theta_i, thetadot_i for every rig metronome, platform) as the
  // state and its time: SI for a physical rig (a scaled rig's rows are scaled: scaled_model.h).
  Vec stateFromRow(const std::vector<double>& row) const;
  double timeFromRow(const std::vector<double>& row) const { return row[0]; }

 private:
  // One pendulum's terms at a state: c = m L cos theta, r = -m g L sin theta - b thetadot (e1.1a).
  struct PendulumTerms {
    double s = 0, co = 0, w = 0, c = 0, r = 0, inv_I = 0;
  };
  // G (every force on x but friction) and S = sum c_j^2 / I_j, with their gradients in y
  struct PlatformSums {
    double G = 0.0, S = 0.0;
    Vec dG, dS;
  };
  // the platform's acceleration a (0 when it does not move), Meff, its gradients in y and in p
  struct Acceleration {
    double a = 0.0, meff = 0.0;
    Vec dy, dp;
  };
  // Each pendulum's terms at y (into terms_); the calls below read them.
  void pendulumTerms(const double* y) const;
  void platformSums(double x, PlatformSums& out) const;
  // out += wG dG/dp + wS dS/dp
  void addPlatformSumsParameters(double x, double wG, double wS, Vec& out) const;
  // false when the platform does not move in `mode` (a = 0, both gradients 0)
  bool acceleration(const double* y, PlatformMode mode, Acceleration& acc) const;
  // an impulse p on the pins (the ticked ones' sides): the jump's derivative in p, into D
  void impulseParameterJacobian(const Vec& y, const std::vector<double>& pins,
                                const std::vector<int>& ticked, Mat& D) const;

  network::NetworkEquations eq_;
  FrictionLaw law_;
  double normal_force_ = 0.0;  // M g (N)
  int n_ = 0, d_ = 0;
  ParameterLayout pl_;
  Vec p_;
  double k_spring_ = 0.0;  // N/m
  bool law_partials_ = false;
  // scratch (the variational equations are evaluated at every stage of every step)
  mutable FrictionPartials fp_;
  mutable std::vector<PendulumTerms> terms_;
  mutable PlatformSums sums_;
  mutable Acceleration acc_;
};

}  // namespace metrosync::orbit
