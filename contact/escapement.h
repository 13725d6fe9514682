// The escapement (eq. e1.1a's impulse): when a pendulum passes +-theta_c outwards, its pin gets
// the generalized impulse side * J-bar (side = +1 at +theta_c, -1 at -theta_c). One rule for both
// engines and the event resolver (sim/events/).
//
// Witness (rising): side * theta - theta_c crosses zero upwards when the pendulum passes the
// critical angle outwards.
// Due: |theta| >= theta_c (1 - kSlack) with an outward rate. The slack lets every pendulum whose
// crossing lies within a relative 1e-9 of the event join its window: near-simultaneous crossings
// (identical metronomes in antiphase cross within ~1e-16 of each other, and a localization window
// ends a few ulps past the earliest root) are applied as one combined impulse, whatever their
// order in the window. 1e-9 is far below any accuracy the engines run at (>= 1e-14 relative in
// time, the tick moved by at most 1e-9 theta_c / |thetadot|, an O(1e-9 J) change of the state),
// yet far above the rounding of the witnesses (~1e-14 near a root of the dense output).
// Consumed: a tick applied early (inside the slack, witness still < 0) must not fire again when
// its witness then crosses zero: the side is disarmed by its tick and re-armed only once the
// pendulum is back inside theta_c (1 - kSlack), a condition on the state, never on time.
#pragma once

namespace metrosync {

struct Escapement {
  // relative slack of the tick condition (see above)
  static constexpr double kSlack = 1e-9;

  double theta_c = 0.0;  // critical angle (rad, or scaled)
  double impulse = 0.0;  // J-bar: generalized impulse magnitude; 0 = no escapement

  bool active() const { return impulse > 0; }
  static int side(double theta) { return theta > 0 ? 1 : -1; }
  // The witness of the tick on `side`, rising through zero at the crossing.
  double witness(double theta, int side_) const { return side_ * theta - theta_c; }
  // The tick condition at an event.
  bool due(double theta, double thetadot) const {
    const double a = theta >= 0 ? theta : -theta;
    return active() && a >= theta_c * (1 - kSlack) && theta * thetadot > 0;
  }
  // A side disarmed by its tick is armed again once the pendulum is back inside the slack band.
  bool rearms(double theta, int side_) const { return side_ * theta < theta_c * (1 - kSlack); }
  // The generalized impulse of a tick at theta.
  double tickImpulse(double theta) const { return side(theta) * impulse; }
};

}  // namespace metrosync
