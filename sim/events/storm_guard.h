// The one event-storm (Zeno) rule of both engines: more than `max_events` discontinuities (event
// windows, plastic stops, redone steps) while time advances by less than `window` fast periods
// ends the run, incomplete. A physical event sequence needs time to advance (a tick per half
// period, a few switches per tick): a thousand in a millionth of a period is an accumulation
// point of events that no integrator can pass.
#pragma once

#include <string>

namespace metrosync {

class StormGuard {
 public:
  static constexpr long kMaxEvents = 1000;
  static constexpr double kWindowPeriods = 1e-6;

  // period: the fast period in the engine's time unit
  explicit StormGuard(double period, long max_events = kMaxEvents,
                      double window_periods = kWindowPeriods)
      : max_events_(max_events),
        window_periods_(window_periods),
        window_(window_periods * period) {}

  // Notes a discontinuity at t; true once the storm rule is met (the run must stop).
  bool note(double t) {
    if (t - burst_start_ > window_) {
      burst_start_ = t;
      count_ = 0;
    }
    return ++count_ > max_events_;
  }

  // The failure message.
  std::string why() const;

 private:
  long max_events_;
  double window_periods_;
  double window_;  // in the engine's time unit
  double burst_start_ = -1e300;
  long count_ = 0;
};

}  // namespace metrosync
