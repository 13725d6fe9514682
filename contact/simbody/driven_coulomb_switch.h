// One change of the platform's mode in the driven Coulomb problem (contact/simbody/
// driven_coulomb.h measures them, driven_coulomb_harness.h records them).
#pragma once

namespace metrosync {

struct DrivenCoulombSwitch {
  double t = 0.0;  // instant (drive time), in the measured period
  int mode = 0;    // platform mode after it: 1 slipping +, -1 slipping -, 0 stuck
};

}  // namespace metrosync
