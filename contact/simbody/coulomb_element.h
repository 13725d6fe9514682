// The thin Simbody adapter of SetValuedLaw (contact/set_valued_law.h): a Force::Custom element on
// the platform's slider. The platform's mode (stuck, slipping right, slipping left) is a discrete
// state variable; while slipping the element applies the kinetic force -bound*sign(xdot); while
// stuck the slider is locked at zero velocity and the lock's generalized force is the static
// friction that holds it. Mode switches are made by the event resolver (sim/events/), never here.
#pragma once

#include <Simbody.h>

#include "contact/set_valued_law.h"

namespace metrosync {

class CoulombElement : public SimTK::Force::Custom::Implementation {
 public:
  CoulombElement(const SimTK::GeneralForceSubsystem& forces,
                 const SimTK::MobilizedBody::Slider& slider, SetValuedLaw law)
      : forces_(forces), slider_(slider), law_(law) {}

  const SetValuedLaw& law() const { return law_; }
  PlatformMode mode(const SimTK::State& s) const;

  // Stick: lock the slider at zero velocity (sets xdot = 0). Lowers the stage to Model.
  void stick(SimTK::State& s) const;
  // Slip in `mode` (must not be Stuck): unlock the slider if locked.
  void slip(SimTK::State& s, PlatformMode mode) const;

  // The force friction must supply to keep the platform still (needs Acceleration stage with
  // the slider locked): minus the lock's generalized force.
  double holdingForce(const SimTK::State& s) const;

  // The platform is at rest (xdot set to 0): stuck if friction can hold it, otherwise slipping
  // the way the other forces push it. Realizes `s` to Acceleration. Returns the new mode.
  PlatformMode settleAtRest(const SimTK::System& system, SimTK::State& s) const;

  // The switching rule at a platform event, decided on the state alone: a stuck platform whose
  // holding force has reached the bound slips; a slipping platform whose velocity has reached
  // zero (or reversed) settles at rest. Returns the new mode (unchanged if no rule applies).
  PlatformMode resolveSwitch(const SimTK::System& system, SimTK::State& s) const;

  // Event witness (falls through zero at a switch; needs Acceleration stage):
  // slipping: mode * xdot (the platform stops); stuck: bound - |holding force| (it breaks free).
  double witness(const SimTK::State& s) const;

  void calcForce(const SimTK::State& s, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                 SimTK::Vector_<SimTK::Vec3>& particleForces,
                 SimTK::Vector& mobilityForces) const override;
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }
  void realizeTopology(SimTK::State& s) const override;

 private:
  void setMode(SimTK::State& s, PlatformMode m) const;

  const SimTK::GeneralForceSubsystem& forces_;
  SimTK::MobilizedBody::Slider slider_;
  SetValuedLaw law_;
  mutable SimTK::DiscreteVariableIndex mode_index_;
};

}  // namespace metrosync
