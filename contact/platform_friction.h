// The law between the platform and the table as both engines see it, in their units (newtons):
// a set-valued law (stick/slip, contact/set_valued_law.h) or a smooth force of the velocity, or
// none, or a platform bolted to the table. A law value (contact/friction_law.h) makes one at a
// given normal force; the engines query only this type: minimal_equations.cpp (direct engine),
// the event resolver (sim/events/) and the Simbody elements (contact/simbody/).
#pragma once

#include "contact/platform_mode.h"
#include "contact/set_valued_law.h"

namespace metrosync {

// Viscous platform friction F = -c v (the earlier models' law).
struct ViscousLaw {
  double c = 0.0;
  double force(double v) const { return -c * v; }
};

struct PlatformFriction {
  enum class Kind { SetValued, Viscous, None, Fixed };
  Kind kind = Kind::None;
  SetValuedLaw dry;    // kind == SetValued
  ViscousLaw viscous;  // kind == Viscous

  // Set-valued at v = 0 (a stuck platform holds with any force up to a bound): the engines keep a
  // platform mode and locate stick/slip events. The other laws are smooth forces of v.
  bool setValued() const { return kind == Kind::SetValued; }
  // The platform can move at all (not bolted to the table).
  bool platformMoves() const { return kind != Kind::Fixed; }

  // Friction force on a platform moving at v in `mode` (mode matters for a set-valued law only:
  // its kinetic force while slipping, 0 while stuck, where the holding force is a constraint).
  double force(double v, PlatformMode mode) const {
    switch (kind) {
      case Kind::SetValued:
        return dry.kineticForce(mode);
      case Kind::Viscous:
        return viscous.force(v);
      case Kind::None:
      case Kind::Fixed:
        return 0.0;
    }
    return 0.0;
  }

  // Power taken out of the system (>= 0): -F v.
  double power(double v, PlatformMode mode) const { return -force(v, mode) * v; }
};

}  // namespace metrosync
