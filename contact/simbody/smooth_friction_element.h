// The Simbody adapter of a smooth platform law (PlatformFriction with setValued() false and a
// force: viscous, and any law added beside it in contact/): a Force::Custom element applying the
// law's force PlatformFriction::force(xdot) on the platform's slider. A set-valued law has its
// own element with modes (coulomb_contact.h).
#pragma once

#include <Simbody.h>

#include "contact/platform_friction.h"

namespace metrosync {

class SmoothFrictionElement : public SimTK::Force::Custom::Implementation {
 public:
  SmoothFrictionElement(const SimTK::MobilizedBody::Slider& slider, PlatformFriction friction)
      : slider_(slider), friction_(friction) {}

  void calcForce(const SimTK::State& s, SimTK::Vector_<SimTK::SpatialVec>&,
                 SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector& mobilityForces) const override {
    const double v = slider_.getOneU(s, SimTK::MobilizerUIndex(0));
    slider_.applyOneMobilityForce(s, 0, friction_.force(v, PlatformMode::Stuck), mobilityForces);
  }
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }
  // the force depends on the velocity
  bool dependsOnlyOnPositions() const override { return false; }

 private:
  SimTK::MobilizedBody::Slider slider_;
  PlatformFriction friction_;
};

}  // namespace metrosync
