// The full model (e1.1a-c) in minimal coordinates, physical units, for every rig: a network of
// platforms (models/network.h, docs/networks.md), a single board being a network of one: each
// platform's absolute position x_p and one angle per swinging pendulum. In absolute coordinates
// platforms share no inertia, so the mass matrix is block-diagonal with one arrow per platform,
//   [[M_p, c_p^T], [c_p, diag(I_p)]],  c_j = m_j L_j cos theta_j,  M_p = rig.totalMass(),
// and each arrow is solved in O(its pendulums) by its Schur complement Meff_p = M_p - sum c_j^2/I_j
// (models/platform_arrow.h). Platforms interact through forces only:
//   ground spring and damper  -k_p x_p - c_p xdot_p  (a platform on the table)
//   couplings                 -k (x_a - x_b) - c (xdot_a - xdot_b) on a, the opposite on b
//   friction of the contact under p (the table, or the platform p rests on): F_p(u_p), u_p = xdot_p
//     - xdot_below, on p, and -F_p on the platform below; Coulomb's bound is mu-bar_p g times the
//     mass p carries (eq. frictionlaw on each contact).
// A stuck Coulomb contact holds u_p' = 0 with a holding force lambda_p: several stuck contacts give
// one small linear system for the lambdas (contacts x contacts; platforms are few).
// A fixed platform keeps its x = xdot = 0 entries but has no equation (it never moves).
//
// State y: models/network_layout.h (the dampers' work only in a network with a damper).
//
// A single board -- one platform on the table, no damper, no coupling (singleArrow()) -- has its
// own entry points, with one platform mode and N known to the compiler: its arrow's fused pass
// (PlatformArrow::tableRates), the holding force and its rate in closed form. They give the bits
// the single rig always had; the general ones agree with them to round-off.
#pragma once

#include <vector>

#include "contact/escapement.h"
#include "contact/platform_friction.h"
#include "models/network.h"
#include "models/network_layout.h"
#include "models/platform_arrow.h"

namespace metrosync::network {

struct Block {
  bool moves = false;         // not fixed
  int below = -1;             // the platform it rests on; -1: the table
  double mass = 0.0;          // M_p (kg): the board with its metronomes
  double k = 0.0, c = 0.0;    // ground spring (N/m) and damper (N s/m)
  PlatformFriction friction;  // the contact under it
  int first = 0, count = 0;   // its swinging pendulums: [first, first + count)
};

class NetworkEquations {
 public:
  explicit NetworkEquations(const Network& net);
  // a rig as the network of one it is (models/network.h, networkOfOne)
  explicit NetworkEquations(const Rig& rig);

  const Layout& layout() const { return lay_; }
  int numPlatforms() const { return lay_.platforms; }
  const Block& block(int p) const { return blocks_[p]; }
  const PendulumConstants& pendulum(int j) const { return pend_[j]; }
  Escapement escapement(int j) const { return {pend_[j].theta_c, pend_[j].impulse}; }
  // platform p's contact is Coulomb and currently stuck in `modes`
  bool stuck(int p, const std::vector<PlatformMode>& modes) const;
  // u_p = xdot_p - xdot_below (the contact's slip velocity)
  double slipVelocity(const double* y, int p) const;

  // dy/dt with the contacts in `modes` (Coulomb contacts only: Stuck holds u_p' = 0).
  void rhs(const double* y, const std::vector<PlatformMode>& modes, double* dy) const;
  // The holding force lambda_p of every stuck contact (0 for the others), on y.
  std::vector<double> holdingForces(const double* y, const std::vector<PlatformMode>& modes) const;

  // A generalized impulse: pin[j] on pendulum j's pin (N m s), contact[p] on platform p and its
  // opposite on the platform below (N s), every platform free (dry friction gives no impulse).
  // Returns the kinetic energy jump (J).
  double applyImpulse(double* y, const std::vector<double>& pin,
                      const std::vector<double>& contact) const;
  // The slip velocity change of contact p per unit impulse on it: 1/Meff_p + 1/Meff_below.
  double contactMobility(const double* y, int p) const;
  // Horizontal momentum sum_p (M_p xdot_p + sum_j c_j thetadot_j) (N s).
  double momentum(const double* y) const;
  // Kinetic + potential energy (J): gravity as in platform_arrow.h, every spring's energy.
  double energy(const double* y) const;

  // --- a single board: one platform on the table, no damper, no coupling ----------------------
  bool singleArrow() const { return single_arrow_; }
  // its platform's arrow, and the arrow's facts
  const PlatformArrow& arrow() const { return arrows_[0]; }
  int numSwinging() const { return lay_.n; }
  bool hasPlatform() const { return blocks_[0].moves; }
  const PlatformFriction& friction() const { return blocks_[0].friction; }
  // the set-valued law's bounds (friction().setValued() only)
  const SetValuedLaw& dryFriction() const { return blocks_[0].friction.bounds(); }
  double totalMass() const { return blocks_[0].mass; }
  // dy/dt in the platform's mode (only a set-valued law uses it: Stuck holds xdot = 0, a slip
  // feels the law's slip force); dy gets the damping and friction power too. N == numSwinging()
  // (1 .. PlatformArrow::kMaxFixedN) or kAnyN: the same operations in the same order.
  static constexpr int kAnyN = PlatformArrow::kAnyN, kMaxFixedN = PlatformArrow::kMaxFixedN;
  template <int N>
  void rhsN(const double* y, PlatformMode mode, double* dy) const;
  // (beside rhs(y, modes, dy): a braced {mode} argument picks this one)
  void rhs(const double* y, PlatformMode mode, double* dy) const { rhsN<kAnyN>(y, mode, dy); }
  // H = -G: the force friction must supply to keep the platform still (xdot = 0 in y), and dH/dt
  // along the motion with the platform held still (xddot = 0).
  double holdingForce(const double* y) const {
    return arrows_[0].tableHoldingForce(y[0], y + 2, y + 2 + lay_.n);
  }
  double holdingForceRate(const double* y) const {
    return arrows_[0].tableHoldingForceRate(y + 2, y + 2 + lay_.n);
  }
  // applyImpulse() with pin_impulse (n x 1) and platform_impulse on x
  double applyImpulse(double* y, const double* pin_impulse, double platform_impulse) const {
    return arrows_[0].applyImpulse(y + 2, y + 1, y + 2 + lay_.n, pin_impulse, platform_impulse);
  }
  // (M^-1)_xx = 1 / Meff (1/kg)
  double platformMobility(const double* y) const { return arrows_[0].mobility(y + 2); }

 private:
  // Schur pass of platform p: Meff_p, and G_p (every force on x_p but friction, after eliminating
  // its pendulums' accelerations); stores c_j, r_j.
  void schur(const double* y, int p, double& meff, double& g) const;
  // Meff_p and the free accelerations of every platform (friction of slipping/smooth contacts in),
  // then the stuck contacts' lambdas solved in; a[p] the final accelerations.
  void accelerations(const double* y, const std::vector<PlatformMode>& modes,
                     std::vector<double>& a, std::vector<double>* lambda) const;
  double inverseMass(const double* y, int p) const;

  Layout lay_;
  std::vector<Block> blocks_;
  // each platform's arrow (its Schur pass, pendulum accelerations, impulses, energy), composed
  std::vector<PlatformArrow> arrows_;
  bool single_arrow_ = false;
  std::vector<PendulumConstants> pend_;
  std::vector<Coupling> couplings_;
  mutable std::vector<double> meff_;
};

}  // namespace metrosync::network
