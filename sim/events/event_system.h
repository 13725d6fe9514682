// What an engine exposes to the event resolver (sim/events/resolver.h), on the state at the end
// of a localization window. The direct engine implements it on its state vector
// (sim/engines/direct/), the Simbody engine on a SimTK::State (sim/engines/simbody/); the
// resolver's tests on a two-degree-of-freedom fake (tests/events/).
// Pendulums are numbered 0 .. numPendulums()-1 in the engine's own order.
#pragma once

#include <vector>

#include "contact/friction_law.h"

namespace metrosync {

class EventSystem {
 public:
  virtual ~EventSystem() = default;

  virtual double theta(int j) const = 0;
  virtual double thetadot(int j) const = 0;
  virtual double xdot() const = 0;

  // The platform's mode (Coulomb only). setMode(Stuck) holds the platform at xdot = 0 (the
  // resolver calls it only once xdot is 0 to rounding: after a plastic stop); a slip mode lets it
  // move with the kinetic force.
  virtual PlatformMode mode() const = 0;
  virtual void setMode(PlatformMode m) = 0;
  // The force friction must supply to keep the platform still, on the current state with
  // xdot = 0 (called only in mode Stuck).
  virtual double holdingForce() = 0;

  // One combined generalized impulse through the mass matrix with the platform free:
  // pin_impulse[j] on pendulum j's pin, platform_impulse on x. Returns the kinetic energy jump.
  virtual double applyImpulse(const std::vector<double>& pin_impulse, double platform_impulse) = 0;
  // (M^-1)_xx: the platform's velocity change per unit impulse on x, the platform free.
  virtual double platformMobility() = 0;

  // Writes an event row ("tick", "stick", "slip") with the current state.
  virtual void eventRow(const char* kind) = 0;

  // The event record (events.csv, docs/outputs.md), one per tick of each pendulum and per
  // platform switch, with the state just before and just after it: the resolver calls
  // snapshotBefore() before each change it may record and recordEvent() once the change is made.
  // kind: "tick" (pendulum: engine order), "stick" or "slip" (pendulum -1: the platform).
  // An engine that records nothing keeps the defaults.
  virtual void snapshotBefore() {}
  virtual void recordEvent(const char* kind, int pendulum) {}
};

}  // namespace metrosync
