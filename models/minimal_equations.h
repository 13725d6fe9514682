// The full model (e1.1a-c, generalised to N metronomes) in minimal coordinates, physical units:
// the platform position x and one angle theta_j per swinging pendulum. Locked metronomes (paper
// section 3A) have no coordinate: their whole mass rides with the platform.
//
//   kinetic energy T = 1/2 M xdot^2 + sum_j c_j xdot thetadot_j + 1/2 sum_j I_j thetadot_j^2,
//   c_j = m_j L_j cos theta_j, M = the platform with everything on it (Rig::totalMass()),
// so the mass matrix is [[M, c^T], [c, diag(I)]] and Lagrange's equations read
//   M xddot + sum_j c_j thetaddot_j - sum_j m_j L_j sin theta_j thetadot_j^2 = F - k x   (e1.1c)
//   I_j thetaddot_j + c_j xddot = r_j,  r_j = -m_j g L_j sin theta_j - nu-bar_j L_j^2 thetadot_j
//                                                                                  (e1.1a, b)
// Eliminating thetaddot_j (the Schur complement of diag(I)) gives the platform first, in O(N):
//   Meff xddot = G + F,  Meff = M - sum_j c_j^2 / I_j,
//   G = sum_j m_j L_j sin theta_j thetadot_j^2 - sum_j c_j r_j / I_j - k x   (F: the law's force)
// then thetaddot_j = (r_j - c_j xddot) / I_j. G is the push of everything but friction: a stuck
// platform needs the holding force H = -G from friction (SetValuedLaw's holding_force).
//
// State vector y, (dim x 1): x, xdot, theta_1..theta_n, thetadot_1..thetadot_n (n swinging
// pendulums, in rig order), then two quadratures for the energy ledger: the work done by the
// pivot dampers and by platform friction (J).
#pragma once

#include <vector>

#include "contact/escapement.h"
#include "contact/platform_friction.h"
#include "models/rig.h"

namespace metrosync {

// The platform's law from the rig at the normal force M g (eq. frictionlaw: a set-valued law's
// bounds are its coefficients times M g), M the platform with everything on it. Both engines
// take it from here.
PlatformFriction platformFriction(const Rig& rig);

}  // namespace metrosync

namespace metrosync::direct {

struct StateLayout {
  int n = 0;  // swinging pendulums
  static constexpr int kX = 0, kV = 1;
  // a network of one platform's slots (models/network_equations.h, network::Layout)
  static constexpr int platforms = 1;
  static constexpr int x(int) { return kX; }
  static constexpr int v(int) { return kV; }
  int theta(int j) const { return 2 + j; }
  int omega(int j) const { return 2 + n + j; }
  int dampingWork() const { return 2 + 2 * n; }
  int frictionWork() const { return 3 + 2 * n; }
  int dim() const { return 4 + 2 * n; }
  int mechanical() const { return 2 + 2 * n; }  // x, xdot, angles and rates
};

// One pendulum's constants.
struct PendulumConstants {
  int rig_index = 0;     // index in Rig::metronomes
  double mL = 0.0;       // m_j L_j (kg m)
  double mgL = 0.0;      // m_j g L_j (N m)
  double inertia = 0.0;  // I_j about the pivot (kg m^2)
  double inv_inertia = 0.0;
  double damping = 0.0;  // nu-bar_j L_j^2 (N m s)
  double theta_c = 0.0;  // escapement angle (rad)
  double impulse = 0.0;  // J-bar_j (N m s); 0 = no escapement
};

class MetronomeEquations {
 public:
  explicit MetronomeEquations(const Rig& rig);

  const StateLayout& layout() const { return layout_; }
  int numSwinging() const { return layout_.n; }
  const PendulumConstants& pendulum(int j) const { return pend_[j]; }
  bool hasPlatform() const { return has_platform_; }
  const PlatformFriction& friction() const { return friction_; }
  // the set-valued law's bounds (friction().setValued() only)
  const SetValuedLaw& dryFriction() const { return friction_.bounds(); }
  Escapement escapement(int j) const { return {pend_[j].theta_c, pend_[j].impulse}; }
  double totalMass() const { return mass_; }

  // dy/dt in the given platform mode (only a set-valued law uses it: Stuck holds xdot = 0, a slip
  // feels the law's slip force). dy also gets the damping and friction power.
  void rhs(const double* y, PlatformMode mode, double* dy) const { rhsN<kAnyN>(y, mode, dy); }
  // The same with the number of swinging pendulums known to the compiler (N == numSwinging(),
  // 1 .. kMaxFixedN), or kAnyN: the same operations in the same order, so the same bits.
  static constexpr int kAnyN = -1, kMaxFixedN = 8;
  template <int N>
  void rhsN(const double* y, PlatformMode mode, double* dy) const;

  // H = -G: the force friction must supply to keep the platform still (with xdot = 0 in y).
  double holdingForce(const double* y) const;
  // dH/dt along the motion with the platform held still (xddot = 0).
  double holdingForceRate(const double* y) const;

  // One combined generalized impulse: pin_impulse[j] on each pendulum's pin (N m s, (n x 1)) and
  // platform_impulse on x (N s), through the full mass matrix [[M, c^T], [c, diag(I)]] with the
  // platform free to move (dry friction, bounded, gives no impulse). A fixed platform takes none
  // of it. Returns the jump of the kinetic energy (J): the work of the impulse.
  double applyImpulse(double* y, const double* pin_impulse, double platform_impulse) const {
    return applyImpulseAt(y + 2, y + 1, y + 2 + layout_.n, pin_impulse, platform_impulse);
  }
  // (M^-1)_xx = 1 / Meff: the platform's velocity change per unit impulse on x (1/kg).
  double platformMobility(const double* y) const { return platformMobilityAt(y + 2); }

  // Kinetic + potential energy (J), with Simbody's zero: gravity m g y of each pendulum's centre
  // of mass, y = -L cos theta below its pivot; the platform spring 1/2 k x^2.
  double energy(const double* y) const { return energyAt(y[0], y[1], y + 2, y + 2 + layout_.n); }

  // --- the same arithmetic on one platform of a network (models/network_equations.h) --------
  // Its state is the platform's x, xdot and its pendulums' angles th and rates w (n x 1 each)
  // wherever they sit in the network's state vector.
  // The arrow's Schur pass: Meff = M - sum_j c_j^2 / I_j and G, every force on x but friction
  // (pendulums and ground spring), as rhs() forms them; keeps c_j and r_j for
  // pendulumAccelerations() (a fixed platform too: its G and Meff are not used).
  void schurPass(const double* th, const double* w, double x, double& meff, double& G) const;
  // thetaddot_j = (r_j - c_j a) / I_j with the platform's acceleration a, after schurPass() on
  // the same state (a = 0 for a platform that does not move).
  void pendulumAccelerations(double a, double* dw) const;
  // sum_j nu-bar_j L_j^2 thetadot_j^2: the pivot dampers' power (W)
  double dampingPower(const double* w) const;
  // applyImpulse() on the platform's parts: v (its xdot; unused when it does not move) and w
  double applyImpulseAt(const double* th, double* v, double* w, const double* pin_impulse,
                        double platform_impulse) const;
  // platformMobility() and energy() on the platform's parts
  double platformMobilityAt(const double* th) const;
  double energyAt(double x, double v, const double* th, const double* w) const;

 private:
  StateLayout layout_;
  std::vector<PendulumConstants> pend_;  // (n x 1)
  bool has_platform_ = false;
  PlatformFriction friction_;
  double mass_ = 0.0;    // M (kg)
  double spring_ = 0.0;  // k (N/m)
  // the pendulums' constants again as arrays (n x 1), for the vectorized loops of rhs()
  std::vector<double> mL_, mgL_, inv_inertia_, damping_;
  // scratch of rhs() and the holding force, (n x 1): sin and cos of the angles, c_j, r_j
  // and the terms of the platform's sums G and sum c_j^2 / I_j
  mutable std::vector<double> sin_, cos_, c_, r_, g_term_, s_term_;
  // sin_ and cos_ of the angles in y (models/vector_trig.h)
  void angleTrig(const double* y) const;
  template <int N>
  void rhsBody(const double* y, PlatformMode mode, double* dy, double* sn, double* cs, double* c,
               double* r, double* g_term, double* s_term) const;
};

}  // namespace metrosync::direct
