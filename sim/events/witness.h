// Witness functions with their direction in their type (after Drake's WitnessFunction): each kind
// of event is the zero crossing of one scalar function of the state, in a declared direction.
// Both engines use these definitions: the Simbody engine sets its TriggeredEventHandlers' trigger
// info from kDirection, the direct engine turns every witness into a rising one with
// risingSign() and locates the crossing on its dense output.
#pragma once

#include "contact/escapement.h"
#include "contact/set_valued_law.h"
#include "models/slow_flow.h"

namespace metrosync {

enum class Direction { Rising, Falling, Both };

// The factor that turns a witness of direction d into one that rises through zero at its event.
// (Both has no such factor: it is returned as is, and either sign change counts.)
constexpr double risingSign(Direction d) {
  return d == Direction::Falling ? -1.0 : 1.0;
}

// Did a witness of direction d cross zero between the values g0 and g1 (an exact zero at the end
// counts, an exact zero at the start does not: it was the previous event)?
constexpr bool crossed(Direction d, double g0, double g1) {
  switch (d) {
    case Direction::Rising:
      return g0 < 0 && g1 >= 0;
    case Direction::Falling:
      return g0 > 0 && g1 <= 0;
    case Direction::Both:
      return (g0 < 0 && g1 >= 0) || (g0 > 0 && g1 <= 0);
  }
  return false;
}

// A tick of pendulum j on `side` (+1 at +theta_c, -1 at -theta_c): rises through zero when the
// pendulum passes the critical angle outwards (contact/escapement.h).
struct TickWitness {
  static constexpr Direction kDirection = Direction::Rising;
  int pendulum = 0;
  int side = 1;
  double value(const Escapement& e, double theta) const { return e.witness(theta, side); }
};

// The platform under a set-valued friction law (contact/set_valued_law.h): falls through zero at
// its next switch.
//   stuck:    the stick margin static bound - |H| (friction can no longer hold it: stick -> slip)
//   slipping: mode * xdot (the slip's velocity reaches zero: it stops or reverses)
struct PlatformWitness {
  static constexpr Direction kDirection = Direction::Falling;
  static double value(const SetValuedLaw& law, PlatformMode mode, double xdot, double holding) {
    if (mode == PlatformMode::Stuck) return law.stickMargin(holding);
    return static_cast<int>(mode) * xdot;
  }
};

// A switching surface of the slow flow (models/slow_flow.h: an escapement's A_i = theta_c,i, the
// platform's s = 1 and s = s_b): rises through zero when the flow passes to the other side of the
// surface from the side `sw.positive` says it is on.
struct SlowFlowSwitchWitness {
  static constexpr Direction kDirection = Direction::Rising;
  static double value(const SlowFlow& flow, const SlowFlowSwitch& sw,
                      const std::complex<double>* z) {
    return (sw.positive ? -1.0 : 1.0) * flow.switchValue(sw, z);
  }
};

}  // namespace metrosync
