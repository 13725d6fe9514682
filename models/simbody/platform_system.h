// The one Simbody system builder of the full model (e1.1a-c, docs/architecture.md): a network of
// platforms (models/network.h, docs/networks.md) assembled as one Simbody MultibodySystem, with
// only what the network needs. A single-platform rig is a network of one (networkOfOne), and gets
// exactly the system it always had:
//   per moving platform a Slider (its board, boxes and locked pendulums as one body), on Ground
//     for a platform on the table (or on a fixed platform), on the slider of the platform below
//     for a stacked one: its coordinate is then the slip of the contact under it;
//   on a table platform's slider its ground spring and damper as mobility forces (its coordinate
//     is its absolute position);
//   per contact the platform's law on its slider: CoulombContact
//   (contact/simbody/coulomb_contact.h)
//     for a set-valued law, SmoothFrictionElement for a smooth one, nothing for a law without a
//     force (none);
//   per swinging pendulum a Pin on its platform's body (on Ground when the platform is fixed;
//     mass m_i, centre of mass at L_i below the pivot, inertia I_i about the pivot), gravity -g y,
//     a pivot damper (torque -nu-bar L^2 thetadot) where nu-bar > 0;
//   the couplings and the ground springs and dampers of stacked platforms as one force element on
//     the platforms' absolute positions and velocities (only when the network has any);
//   and a meter integrating the three dissipations of the energy ledger.
// The state it reports is the direct engine's (network::Layout, absolute x_p and xdot_p).
#pragma once

#include <Simbody.h>

#include <vector>

#include "contact/simbody/coulomb_contact.h"
#include "models/network.h"
#include "models/network_equations.h"

namespace metrosync {

class PlatformSystem {
 public:
  explicit PlatformSystem(const Network& net);
  PlatformSystem(const PlatformSystem&) = delete;
  PlatformSystem& operator=(const PlatformSystem&) = delete;

  const Network& network() const { return net_; }
  const network::NetworkEquations& equations() const { return eq_; }  // layout, blocks, pendulums
  int numPlatforms() const { return static_cast<int>(net_.platforms.size()); }
  int numPendulums() const { return static_cast<int>(pins_.size()); }
  bool moves(int p) const { return eq_.block(p).moves; }
  // platform p's slider hangs on Ground (its coordinate is x_p): it moves and rests on the table
  // or on a fixed platform
  bool onGround(int p) const { return moves(p) && parent_[p] < 0; }
  // the platform that carries swinging pendulum j (network order)
  int platformOf(int j) const { return owner_[j]; }
  // platform p's slider (valid when moves(p)) and its Coulomb contact (nullptr unless Coulomb)
  const SimTK::MobilizedBody::Slider& slider(int p) const { return sliders_[p]; }
  const CoulombContact* contact(int p) const { return contacts_[p]; }
  // swinging pendulum j's pin (network order, models/network_equations.h)
  const SimTK::MobilizedBody::Pin& pin(int j) const { return pins_[j]; }

  // Absolute position and velocity of platform p (0 for a fixed one), the slip velocity of the
  // contact under it, pendulum j's angle and rate (SI).
  double x(const SimTK::State& s, int p) const;
  double xdot(const SimTK::State& s, int p) const;
  double slipVelocity(const SimTK::State& s, int p) const;
  double theta(const SimTK::State& s, int j) const;
  double thetadot(const SimTK::State& s, int j) const;
  // The state in network::Layout (the ledger's quadratures from the meter).
  void layoutState(const SimTK::State& s, std::vector<double>& y) const;
  // Dissipated energies (J): pivot dampers, platform friction, ground and coupling dampers.
  double dampingLoss(const SimTK::State& s) const;
  double frictionLoss(const SimTK::State& s) const;
  double damperLoss(const SimTK::State& s) const;

  SimTK::MultibodySystem& system() { return system_; }
  const SimTK::MultibodySystem& system() const { return system_; }
  const SimTK::SimbodyMatterSubsystem& matter() const { return matter_; }

  // The network's start (absolute x, xdot of each platform as in the rig), realized to Velocity;
  // every contact's mode still to be decided.
  SimTK::State initialState();

 private:
  void addPlatform(int p, std::vector<char>& made);
  void addPendulums(int p);
  bool needsSprings() const;

  Network net_;
  network::NetworkEquations eq_;
  SimTK::MultibodySystem system_;
  SimTK::SimbodyMatterSubsystem matter_;
  SimTK::GeneralForceSubsystem forces_;
  std::vector<SimTK::MobilizedBody::Slider> sliders_;  // (platforms)
  std::vector<const CoulombContact*> contacts_;        // (platforms)
  std::vector<SimTK::MobilizedBody::Pin> pins_;        // (swinging pendulums)
  std::vector<int> owner_;    // (swinging pendulums) the platform carrying each
  std::vector<int> parent_;   // (platforms) the moving platform whose slider carries p's, or -1
  bool has_dampers_ = false;  // a ground or coupling damper: the meter's third quadrature
  SimTK::ZIndex z_;           // the meter's quadratures
};

}  // namespace metrosync
