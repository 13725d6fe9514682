// One platform's arrow of the full model (e1.1a-c, generalised to N metronomes) in minimal
// coordinates, physical units: the platform's position x and one angle theta_j per swinging
// pendulum. Locked metronomes (paper section 3A) have no coordinate: their whole mass rides with
// the platform. The network's equations (models/network_equations.h) compose one arrow per
// platform.
//
//   kinetic energy T = 1/2 M xdot^2 + sum_j c_j xdot thetadot_j + 1/2 sum_j I_j thetadot_j^2,
//   c_j = m_j L_j cos theta_j, M = the platform with everything on it (Rig::totalMass()),
// so the mass matrix is the arrow [[M, c^T], [c, diag(I)]] and Lagrange's equations read
//   M xddot + sum_j c_j thetaddot_j - sum_j m_j L_j sin theta_j thetadot_j^2 = F - k x   (e1.1c)
//   I_j thetaddot_j + c_j xddot = r_j,  r_j = -m_j g L_j sin theta_j - nu-bar_j L_j^2 thetadot_j
//                                                                                  (e1.1a, b)
//   (- d_j thetadot_j |thetadot_j| with air drag, pendulum.air_drag: issue 41)
// Eliminating thetaddot_j (the Schur complement of diag(I)) gives the platform first, in O(N):
//   Meff xddot = G + F,  Meff = M - sum_j c_j^2 / I_j,
//   G = sum_j m_j L_j sin theta_j thetadot_j^2 - sum_j c_j r_j / I_j - k x   (F: the law's force)
// then thetaddot_j = (r_j - c_j xddot) / I_j. G is the push of everything but friction: a platform
// stuck on the table needs the holding force H = -G from friction (SetValuedLaw's holding_force).
//
// Each member reads the platform's parts wherever they sit in the network's state: its x and xdot,
// its pendulums' angles th and rates w (n x 1 each).
#pragma once

#include <vector>

#include "contact/escapement.h"
#include "contact/platform_friction.h"
#include "models/rig.h"

namespace metrosync {

// The platform's law of a rig alone at the normal force M g (eq. frictionlaw: a set-valued law's
// bounds are its coefficients times M g), M the platform with everything on it.
PlatformFriction platformFriction(const Rig& rig);

}  // namespace metrosync

namespace metrosync::network {

// One pendulum's constants.
struct PendulumConstants {
  int rig_index = 0;     // index in Rig::metronomes (the network's global number in a network)
  double mL = 0.0;       // m_j L_j (kg m)
  double mgL = 0.0;      // m_j g L_j (N m)
  double inertia = 0.0;  // I_j about the pivot (kg m^2)
  double inv_inertia = 0.0;
  double damping = 0.0;  // nu-bar_j L_j^2 (N m s)
  double drag = 0.0;     // d_j: air drag, torque -d_j thetadot |thetadot| (N m s^2)
  double theta_c = 0.0;  // escapement angle (rad)
  double impulse = 0.0;  // J-bar_j (N m s); 0 = no escapement
};

// What a platform's arrow gives the ledger: the pivot dampers' and friction's power (W).
struct ArrowPower {
  double damping = 0.0, friction = 0.0;
};

class PlatformArrow {
 public:
  // The platform of `rig` alone, its contact with the table under the law `friction`.
  PlatformArrow(const Rig& rig, const PlatformFriction& friction);

  int numSwinging() const { return n_; }
  const PendulumConstants& pendulum(int j) const { return pend_[j]; }
  bool moves() const { return moves_; }
  const PlatformFriction& friction() const { return friction_; }
  double mass() const { return mass_; }
  bool hasDrag() const { return drag_any_; }  // a pendulum with air drag

  // The platform's rates alone on the table (no damper, no coupling): x' and xdot' into dxv[0..1],
  // theta' into dth, thetadot' into dw, in the contact's mode (Stuck holds xdot = 0, a slip feels
  // the law's slip force), from its x and xdot at xv[0..1]. N == numSwinging() (1 ..
  // kMaxFixedN) or kAnyN: the same operations in the same order, so the same bits. Air drag
  // (hasDrag()) only with kAnyN.
  static constexpr int kAnyN = -1, kMaxFixedN = 8;
  template <int N>
  ArrowPower tableRates(const double* xv, const double* th, const double* w, PlatformMode mode,
                        double* dxv, double* dth, double* dw) const;
  // H = -G on the table: the force friction must supply to keep the platform still (xdot = 0).
  double tableHoldingForce(double x, const double* th, const double* w) const;
  // dH/dt along the motion with the platform held still (xddot = 0).
  double tableHoldingForceRate(const double* th, const double* w) const;

  // The Schur pass: Meff = M - sum_j c_j^2 / I_j and G, every force on x but friction (pendulums
  // and ground spring); keeps c_j and r_j for pendulumAccelerations() (a fixed platform too).
  void schurPass(const double* th, const double* w, double x, double& meff, double& G) const;
  // thetaddot_j = (r_j - c_j a) / I_j with the platform's acceleration a, after schurPass() on
  // the same state (a = 0 for a platform that does not move).
  void pendulumAccelerations(double a, double* dw) const;
  // sum_j (nu-bar_j L_j^2 thetadot_j^2 + d_j |thetadot_j|^3): the pendulums' damping power (W)
  double dampingPower(const double* w) const;
  // One combined generalized impulse: pin_impulse[j] on each pendulum's pin (N m s, (n x 1)) and
  // platform_impulse on x (N s), through [[M, c^T], [c, diag(I)]] with the platform free to move
  // (dry friction, bounded, gives no impulse); a fixed platform takes none of it. v is its xdot
  // (unused when it does not move). Returns the jump of the kinetic energy (J).
  double applyImpulse(const double* th, double* v, double* w, const double* pin_impulse,
                      double platform_impulse) const;
  // (M^-1)_xx = 1 / Meff: the platform's velocity change per unit impulse on x (1/kg); 0 fixed.
  double mobility(const double* th) const;
  // Kinetic + potential energy (J), with Simbody's zero: gravity m g y of each pendulum's centre of
  // mass, y = -L cos theta below its pivot; the ground spring 1/2 k x^2.
  double energy(double x, double v, const double* th, const double* w) const;

 private:
  int n_ = 0;
  std::vector<PendulumConstants> pend_;  // (n x 1)
  bool moves_ = false;
  PlatformFriction friction_;
  double mass_ = 0.0;    // M (kg)
  double spring_ = 0.0;  // k (N/m)
  // the pendulums' constants again as arrays (n x 1), for the vectorized loops
  std::vector<double> mL_, mgL_, inv_inertia_, damping_, drag_;
  bool drag_any_ = false;  // a pendulum with air drag (its terms are computed only then)
  // scratch (n x 1): sin and cos of the angles, c_j, r_j and the terms of the platform's sums G
  // and sum c_j^2 / I_j
  mutable std::vector<double> sin_, cos_, c_, r_, g_term_, s_term_;
  void angleTrig(const double* th) const;  // sin_ and cos_ (models/vector_trig.h)
  template <int N>
  ArrowPower tableDragRates(const double* xv, const double* th, const double* w, PlatformMode mode,
                            double* dxv, double* dth, double* dw) const;
  template <int N, bool Drag>
  ArrowPower tableBody(const double* xv, const double* th, const double* w, PlatformMode mode,
                       double* dxv, double* dth, double* dw, double* sn, double* cs, double* c,
                       double* r, double* g_term, double* s_term) const;
};

}  // namespace metrosync::network
