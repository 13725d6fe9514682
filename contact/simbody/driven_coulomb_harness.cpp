#include "contact/simbody/driven_coulomb_harness.h"

#include <cmath>

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

// The element's one witness; the handler applies the element's own switching rule and records
// every change of mode.
class DrivenCoulombHarness::Switch : public TriggeredEventHandler {
 public:
  Switch(const System& sys, const CoulombElement& c)
      : TriggeredEventHandler(Stage::Acceleration), sys_(sys), c_(c) {
    getTriggerInfo().setTriggerOnRisingSignTransition(false);
  }
  Real getValue(const State& s) const override { return c_.witness(s); }
  void handleEvent(State& s, Real, bool&) const override {
    const PlatformMode before = c_.mode(s);
    const PlatformMode after = c_.resolveSwitch(sys_, s);
    if (after != before) switches.push_back({s.getTime(), static_cast<int>(after)});
  }
  mutable std::vector<DrivenCoulombSwitch> switches;

 private:
  const System& sys_;
  const CoulombElement& c_;
};

DrivenCoulombHarness::DrivenCoulombHarness(double B) {
  Body::Rigid unit(MassProperties(1.0, Vec3(0), UnitInertia(1)));
  slider = MobilizedBody::Slider(matter.Ground(), Transform(), unit, Transform());
  element = new CoulombElement(forces, slider, SetValuedLaw::coulomb(1.0));
  Force::Custom(forces, element);
  Force::Custom(forces, new Drive(slider, B));
  switch_ = new Switch(system, *element);
  system.addEventHandler(switch_);
  system.realizeTopology();
}

const std::vector<DrivenCoulombSwitch>& DrivenCoulombHarness::switches() const {
  return switch_->switches;
}

}  // namespace metrosync
