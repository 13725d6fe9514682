#include "contact/simbody/coulomb_contact.h"

namespace metrosync {

using namespace SimTK;

void CoulombContact::realizeTopology(State& s) const {
  mode_index_ =
      s.allocateDiscreteVariable(forces_.getMySubsystemIndex(), Stage::Dynamics, new Value<int>(0));
}

PlatformMode CoulombContact::mode(const State& s) const {
  return static_cast<PlatformMode>(
      Value<int>::downcast(s.getDiscreteVariable(forces_.getMySubsystemIndex(), mode_index_))
          .get());
}

void CoulombContact::setMode(State& s, PlatformMode m) const {
  if (m == PlatformMode::Stuck) {
    if (!slider_.isLocked(s)) slider_.lock(s, Motion::Acceleration);
  } else if (slider_.isLocked(s)) {
    slider_.unlock(s);
  }
  Value<int>::updDowncast(s.updDiscreteVariable(forces_.getMySubsystemIndex(), mode_index_)).upd() =
      static_cast<int>(m);
}

double CoulombContact::slipVelocity(const State& s) const {
  return slider_.getOneU(s, MobilizerUIndex(0));
}

double CoulombContact::holdingForce(const State& s) const {
  return -slider_.getOneTau(s, MobilizerUIndex(0));
}

double CoulombContact::witness(const State& s) const {
  const PlatformMode m = mode(s);
  if (m == PlatformMode::Stuck) return law().stickMargin(holdingForce(s));
  return static_cast<int>(m) * slipVelocity(s);
}

void CoulombContact::calcForce(const State& s, Vector_<SpatialVec>&, Vector_<Vec3>&,
                               Vector& mobilityForces) const {
  const PlatformMode m = mode(s);
  if (m != PlatformMode::Stuck)
    slider_.applyOneMobilityForce(s, 0, friction_.force(slipVelocity(s), m), mobilityForces);
}

}  // namespace metrosync
