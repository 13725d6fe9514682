// The set-up behind measureDrivenCoulomb (driven_coulomb.h), for code that drives it itself (the
// Simbody tests): a unit mass on a Simbody slider with the full model's Coulomb element at unit
// bound, driven by the prescribed force B sin t (the paper's eq. c1), switched by the element's
// own rules (one witness; resolveSwitch in its handler). Every change of mode is recorded.
#pragma once

#include <Simbody.h>

#include <vector>

#include "contact/simbody/coulomb_element.h"
#include "contact/simbody/driven_coulomb_switch.h"

namespace metrosync {

class DrivenCoulombHarness {
 public:
  explicit DrivenCoulombHarness(double B);

  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter{system};
  SimTK::GeneralForceSubsystem forces{system};
  SimTK::MobilizedBody::Slider slider;
  CoulombElement* element = nullptr;  // owned by `forces`

  // every change of mode so far: its instant and the mode after it
  const std::vector<DrivenCoulombSwitch>& switches() const;

 private:
  class Switch;
  Switch* switch_ = nullptr;  // owned by `system`
};

}  // namespace metrosync
