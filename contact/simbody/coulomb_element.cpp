#include "contact/simbody/coulomb_element.h"

namespace metrosync {

using namespace SimTK;

void CoulombElement::realizeTopology(State& s) const {
  mode_index_ =
      s.allocateDiscreteVariable(forces_.getMySubsystemIndex(), Stage::Dynamics, new Value<int>(0));
}

PlatformMode CoulombElement::mode(const State& s) const {
  return static_cast<PlatformMode>(
      Value<int>::downcast(s.getDiscreteVariable(forces_.getMySubsystemIndex(), mode_index_))
          .get());
}

void CoulombElement::setMode(State& s, PlatformMode m) const {
  Value<int>::updDowncast(s.updDiscreteVariable(forces_.getMySubsystemIndex(), mode_index_)).upd() =
      static_cast<int>(m);
}

void CoulombElement::stick(State& s) const {
  slider_.lockAt(s, 0.0, Motion::Velocity);
  setMode(s, PlatformMode::Stuck);
}

void CoulombElement::slip(State& s, PlatformMode m) const {
  if (slider_.isLocked(s)) slider_.unlock(s);
  setMode(s, m);
}

double CoulombElement::holdingForce(const State& s) const {
  return -slider_.getOneTau(s, MobilizerUIndex(0));
}

PlatformMode CoulombElement::settleAtRest(const System& system, State& s) const {
  stick(s);  // xdot = 0, slider locked at zero velocity
  system.realize(s, Stage::Acceleration);
  const PlatformMode m = law_.modeAtRest(holdingForce(s));
  if (m != PlatformMode::Stuck) {
    slip(s, m);
    system.realize(s, Stage::Acceleration);
  }
  return m;
}

PlatformMode CoulombElement::resolveSwitch(const System& system, State& s) const {
  system.realize(s, Stage::Acceleration);
  const PlatformMode m = mode(s);
  if (m == PlatformMode::Stuck) {
    const double h = holdingForce(s);
    if (!law_.breaksFree(h)) return m;
    const PlatformMode to = SetValuedLaw::slipDirection(h);
    slip(s, to);
    system.realize(s, Stage::Acceleration);
    return to;
  }
  if (static_cast<int>(m) * slider_.getOneU(s, MobilizerUIndex(0)) > 0) return m;
  return settleAtRest(system, s);
}

double CoulombElement::witness(const State& s) const {
  const PlatformMode m = mode(s);
  if (m == PlatformMode::Stuck) return law_.stickMargin(holdingForce(s));
  return static_cast<int>(m) * slider_.getOneU(s, MobilizerUIndex(0));
}

void CoulombElement::calcForce(const State& s, Vector_<SpatialVec>&, Vector_<Vec3>&,
                               Vector& mobilityForces) const {
  const PlatformMode m = mode(s);
  if (m != PlatformMode::Stuck)
    slider_.applyOneMobilityForce(s, 0, law_.kineticForce(m), mobilityForces);
}

}  // namespace metrosync
