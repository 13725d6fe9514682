#include "contact/simbody/driven_coulomb_harness.h"

#include <cmath>

#include "contact/friction_law.h"

namespace metrosync {

namespace {

using namespace SimTK;

// the prescribed drive B sin t on the slider (eq. c1's right-hand side)
class Drive : public Force::Custom::Implementation {
 public:
  Drive(const MobilizedBody::Slider& slider, double B) : slider_(slider), B_(B) {}
  void calcForce(const State& s, Vector_<SpatialVec>&, Vector_<Vec3>&,
                 Vector& mobilityForces) const override {
    slider_.applyOneMobilityForce(s, 0, B_ * std::sin(s.getTime()), mobilityForces);
  }
  Real calcPotentialEnergy(const State&) const override { return 0; }

 private:
  MobilizedBody::Slider slider_;
  double B_;
};

}  // namespace

// The contact's one witness; the handler applies the harness's switching rule and records every
// change of mode.
class DrivenCoulombHarness::Switch : public TriggeredEventHandler {
 public:
  explicit Switch(const DrivenCoulombHarness& h)
      : TriggeredEventHandler(Stage::Acceleration), h_(h) {
    getTriggerInfo().setTriggerOnRisingSignTransition(false);
  }
  Real getValue(const State& s) const override { return h_.contact->witness(s); }
  void handleEvent(State& s, Real, bool&) const override {
    const PlatformMode before = h_.contact->mode(s);
    const PlatformMode after = h_.resolveSwitch(s);
    if (after != before) switches.push_back({s.getTime(), static_cast<int>(after)});
  }
  mutable std::vector<DrivenCoulombSwitch> switches;

 private:
  const DrivenCoulombHarness& h_;
};

PlatformMode DrivenCoulombHarness::settleAtRest(State& s) const {
  slider.setOneU(s, MobilizerUIndex(0), 0.0);
  contact->setMode(s, PlatformMode::Stuck);
  system.realize(s, Stage::Acceleration);
  const PlatformMode m = contact->law().modeAtRest(contact->holdingForce(s));
  if (m != PlatformMode::Stuck) {
    contact->setMode(s, m);
    system.realize(s, Stage::Acceleration);
  }
  return m;
}

PlatformMode DrivenCoulombHarness::resolveSwitch(State& s) const {
  system.realize(s, Stage::Acceleration);
  const PlatformMode m = contact->mode(s);
  if (m == PlatformMode::Stuck) {
    const double h = contact->holdingForce(s);
    if (!contact->law().breaksFree(h)) return m;
    const PlatformMode to = SetValuedLaw::slipDirection(h);
    contact->setMode(s, to);
    system.realize(s, Stage::Acceleration);
    return to;
  }
  if (static_cast<int>(m) * contact->slipVelocity(s) > 0) return m;
  return settleAtRest(s);
}

DrivenCoulombHarness::DrivenCoulombHarness(double B) {
  Body::Rigid unit(MassProperties(1.0, Vec3(0), UnitInertia(1)));
  slider = MobilizedBody::Slider(matter.Ground(), Transform(), unit, Transform());
  contact = new CoulombContact(forces, slider, FrictionLaw::coulomb(1.0).platform(1.0));
  Force::Custom(forces, contact);
  Force::Custom(forces, new Drive(slider, B));
  switch_ = new Switch(*this);
  system.addEventHandler(switch_);
  system.realizeTopology();
}

const std::vector<DrivenCoulombSwitch>& DrivenCoulombHarness::switches() const {
  return switch_->switches;
}

}  // namespace metrosync
