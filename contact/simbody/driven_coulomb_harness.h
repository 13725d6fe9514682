// The set-up behind measureDrivenCoulomb (driven_coulomb.h), for code that drives it itself (the
// Simbody tests): a unit mass on a Simbody slider on Ground with the full model's Coulomb contact
// (coulomb_contact.h) at unit bound, driven by the prescribed force B sin t (the paper's eq. c1),
// switched by the law's rules (one witness, the contact's; resolveSwitch in its handler). Every
// change of mode is recorded.
#pragma once

#include <Simbody.h>

#include <vector>

#include "contact/simbody/coulomb_contact.h"
#include "contact/simbody/driven_coulomb_switch.h"

namespace metrosync {

class DrivenCoulombHarness {
 public:
  explicit DrivenCoulombHarness(double B);

  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter{system};
  SimTK::GeneralForceSubsystem forces{system};
  SimTK::MobilizedBody::Slider slider;
  CoulombContact* contact = nullptr;  // owned by `forces`

  // The mass at rest (a plastic stop against Ground: xdot = 0, the reaction Ground's): stuck if
  // friction can hold it, otherwise slipping the way the drive pushes it. Realizes `s` to
  // Acceleration; returns the new mode.
  PlatformMode settleAtRest(SimTK::State& s) const;
  // The switching rule at the contact's event, decided on the state alone: stuck and the holding
  // force at the bound, it slips; slipping and the velocity at zero (or reversed), it settles at
  // rest. Returns the new mode (unchanged if no rule applies).
  PlatformMode resolveSwitch(SimTK::State& s) const;

  // every change of mode so far: its instant and the mode after it
  const std::vector<DrivenCoulombSwitch>& switches() const;

 private:
  class Switch;
  Switch* switch_ = nullptr;  // owned by `system`
};

}  // namespace metrosync
