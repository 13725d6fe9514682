// The Simbody adapter of a set-valued law (contact/platform_friction.h: its bounds,
// contact/set_valued_law.h, and its slip force) for one contact of a network of
// platforms (docs/networks.md): a Force::Custom element on the slider of the platform above the
// contact, whose coordinate is the slip of that platform relative to what it rests on (the table,
// or the platform below). The contact's mode (stuck, slipping right, slipping left) is a discrete
// state variable; while slipping the element applies the law's slip force at the slip velocity
// (Coulomb's -bound * mode), a force pair
// on the platform and (through the relative slider) the platform below; while stuck the slider's
// ACCELERATION is locked at zero, so that several stuck contacts are held together by one solve
// of Simbody's prescribed motion, and each lock's generalized force is that contact's holding
// force. The slip velocity is kept as it is (zero to rounding after a stop): sticking never
// zeroes a velocity (a plastic stop does, with its reaction), as the direct engine's
// "u' = 0" (models/network_equations.h). Mode switches are made by the event resolver
// (sim/events/), never here.
#pragma once

#include <Simbody.h>

#include "contact/platform_friction.h"

namespace metrosync {

class CoulombContact : public SimTK::Force::Custom::Implementation {
 public:
  CoulombContact(const SimTK::GeneralForceSubsystem& forces,
                 const SimTK::MobilizedBody::Slider& slider, PlatformFriction friction)
      : forces_(forces), slider_(slider), friction_(friction) {}

  // the law's bounds and stick/slip decisions
  const SetValuedLaw& law() const { return friction_.bounds(); }
  PlatformMode mode(const SimTK::State& s) const;
  // Stuck: the slider's acceleration locked at zero (its velocity untouched); a slip: unlocked.
  // Lowers the stage to Model.
  void setMode(SimTK::State& s, PlatformMode m) const;
  // The slip velocity (the slider's generalized speed).
  double slipVelocity(const SimTK::State& s) const;
  // The force friction must supply to keep the contact stuck (Acceleration stage, stuck): minus
  // the lock's generalized force.
  double holdingForce(const SimTK::State& s) const;
  // The contact's witness (sim/events/witness.h PlatformWitness, falling at a switch; needs
  // Acceleration stage): stuck, the stick margin; slipping, mode * slip velocity.
  double witness(const SimTK::State& s) const;

  void calcForce(const SimTK::State& s, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                 SimTK::Vector_<SimTK::Vec3>& particleForces,
                 SimTK::Vector& mobilityForces) const override;
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }
  void realizeTopology(SimTK::State& s) const override;

 private:
  const SimTK::GeneralForceSubsystem& forces_;
  SimTK::MobilizedBody::Slider slider_;
  PlatformFriction friction_;  // a set-valued law
  mutable SimTK::DiscreteVariableIndex mode_index_;
};

}  // namespace metrosync
