// The one event-window resolver of both full-model engines (docs/events.md). An engine locates a
// window (one or more witnesses crossed, sim/events/witness.h), brings its state to the window's
// end, and calls resolve(). In order:
//   1. ticks: every pendulum whose escapement is due on an armed side (contact/escapement.h),
//      whichever witnesses were reported and in whatever order, is applied as ONE combined
//      generalized impulse through the mass matrix with the platform free;
//   2. the platform after the impulse (a set-valued law, contact/set_valued_law.h): a stuck
//      platform still at xdot == 0 exactly stays stuck; any other velocity is a slip its way;
//   3. the law's stick/slip rule on the resulting state: a stuck platform whose holding force
//      has reached the static bound breaks free; a slip whose velocity has reached zero (or
//      passed it) stops; a slip that friction would stop within kPlasticStopPeriods of a period
//      stops at once. Every stop is plastic: friction's impulse on x alone through M^-1, the
//      pendulums taking the reaction, so momentum is exact; then the law's mode at rest.
//   4. counts and event rows.
// No tolerance ever zeroes a velocity without its reaction, and nothing is disarmed by time.
#pragma once

#include <vector>

#include "contact/escapement.h"
#include "contact/platform_friction.h"
#include "sim/events/event_system.h"

namespace metrosync {

// What one window did, for the engine's counts and energy ledger.
struct WindowOutcome {
  std::vector<int> ticked;     // pendulums that ticked (engine order)
  double escapement_in = 0.0;  // kinetic energy jump of the combined tick impulse
  double friction_out = 0.0;   // kinetic energy removed by plastic stops
  int stick_slip = 0;          // stick <-> slip transitions
  int slip_reversals = 0;      // slip+ <-> slip- without a stop in between
  int plastic_stops = 0;       // micro-slips ended at once, within the window
  bool changed() const { return !ticked.empty() || stick_slip || slip_reversals || plastic_stops; }
};

class EventResolver {
 public:
  // A slip that friction alone would stop within this fraction of a fast period is stopped at
  // once (plastically). Integrating it would take steps of that size for a displacement of
  // O(1e-12 period^2 * deceleration), far below every accuracy the engines run at; such slips
  // come from (nearly) cancelling ticks and from huge friction coefficients.
  static constexpr double kPlasticStopPeriods = 1e-6;

  // escapements: one per pendulum (engine order); friction: the platform's law (the stick/slip
  // rules run only for a set-valued one, contact/set_valued_law.h); period: the fast period in the
  // engine's time unit. `theta0` is the start state's angles: a side already past its critical
  // angle at the start is disarmed.
  EventResolver(std::vector<Escapement> escapements, const PlatformFriction& friction,
                double period, const std::vector<double>& theta0);

  // Resolves a window on sys's state. platform_reported: the platform's witness crossed.
  WindowOutcome resolve(EventSystem& sys, bool platform_reported);

  // Re-arms the sides whose pendulums are back inside their critical angle (call on every state
  // the engine visits between windows: step ends).
  void rearm(const EventSystem& sys);
  void rearm(int j, double theta) {  // (inline: called for every pendulum at every step end)
    for (int side : {-1, 1}) {
      char& a = armed_[2 * j + (side > 0)];
      if (!a && esc_[j].rearms(theta, side)) a = 1;
    }
  }
  // Is the tick of pendulum j on `side` armed (its witness may report)?
  bool armed(int j, int side) const { return armed_[2 * j + (side > 0)]; }

  // A platform whose support moved under it (a network of platforms: an impulse on the platform
  // it rests on changed its slip velocity): its mode after that impulse, as after its own ticks
  // (step 2, micro-slips stopped plastically), then the stick/slip rule (step 3).
  WindowOutcome settleAfterSupportImpulse(EventSystem& sys);

  // The platform's mode at the start: at xdot == 0 the law's mode at rest (a "slip" row if it
  // breaks free at once: the start is not counted as a switch), otherwise a slip its way.
  PlatformMode settleAtStart(EventSystem& sys) const;

 private:
  const std::vector<int>& dueTicks(const EventSystem& sys);  // in due_
  void applyTicks(EventSystem& sys, const std::vector<int>& due, WindowOutcome& out);
  void modeAfterImpulse(EventSystem& sys, PlatformMode before, WindowOutcome& out);
  void coulombRule(EventSystem& sys, WindowOutcome& out);
  // a slip at v in mode m (the platform's) that friction ends at once
  bool microSlip(EventSystem& sys, double v, PlatformMode m) const;
  const SetValuedLaw& law() const { return friction_.bounds(); }  // set_valued_ only
  // stops the platform (plastic impulse on x), then the law's mode at rest
  void stopAndSettle(EventSystem& sys, PlatformMode before, WindowOutcome& out);
  static void countSwitch(EventSystem& sys, PlatformMode before, PlatformMode after,
                          WindowOutcome& out);

  std::vector<Escapement> esc_;
  bool set_valued_;            // the platform's law has stick and slip (else no rule applies)
  PlatformFriction friction_;  // the platform's law: its bounds (law()), its slip force
  double period_;
  std::vector<char> armed_;  // (2n x 1): [2j] side -1, [2j+1] side +1
  // scratch of one window, kept so that a window allocates nothing: the due ticks, (n x 1)
  // generalized impulses on the pins
  std::vector<int> due_;
  std::vector<double> impulse_;
};

}  // namespace metrosync
