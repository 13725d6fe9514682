// The law between the platform and the table, as both engines see it: one value type that says
// whether the law is set-valued (needs modes and switching events: Coulomb) and what force and
// power it gives on a moving platform (the smooth part, every law).
//
// To add a law: a value type beside CoulombLaw / ViscousLaw in contact/, a FrictionLaw name
// (contact/friction_law.h), its branch in force() and setValued() here, and its keys in the rig
// loader (yaml/). The engines query only this type: minimal_equations.cpp (direct engine) and the
// Simbody elements (contact/simbody/) need no change for a smooth law.
#pragma once

#include "contact/coulomb.h"
#include "contact/friction_law.h"

namespace metrosync {

struct PlatformFriction {
  FrictionLaw law = FrictionLaw::None;
  CoulombLaw coulomb;  // law == Coulomb
  ViscousLaw viscous;  // law == Viscous

  // Set-valued at v = 0 (a stuck platform holds with any force up to a bound): the engines keep a
  // platform mode and locate stick/slip events. The other laws are smooth forces of v.
  bool setValued() const { return law == FrictionLaw::Coulomb; }
  // The platform can move at all (not bolted to the table).
  bool platformMoves() const { return law != FrictionLaw::Fixed; }

  // Friction force on a platform moving at v in `mode` (mode matters for Coulomb only: its
  // kinetic force while slipping, 0 while stuck, where the holding force is a constraint).
  double force(double v, PlatformMode mode) const {
    switch (law) {
      case FrictionLaw::Coulomb:
        return coulomb.slipForce(mode);
      case FrictionLaw::Viscous:
        return viscous.force(v);
      case FrictionLaw::None:
      case FrictionLaw::Fixed:
        return 0.0;
    }
    return 0.0;
  }

  // Power taken out of the system (>= 0): -F v.
  double power(double v, PlatformMode mode) const { return -force(v, mode) * v; }
};

}  // namespace metrosync
