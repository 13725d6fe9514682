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
  // The sustained tier, for an integrator that resolves a storm coarsely (Simbody's steps around
  // a 1.6 GHz ringing of yaml/rigs/hard/storm.yaml come ~5e-10 s apart: about 600 windows per
  // millionth of a period, never 1000, so the burst rule above never trips while the run crawls
  // through 10^6 reversals). Twenty thousand discontinuities within a ten-thousandth of a period
  // is still four orders of magnitude above any physical sequence (a few per half period per
  // metronome) and trips such a storm after seconds of CPU.
  static constexpr long kSustainedEvents = 20000;
  static constexpr double kSustainedWindowPeriods = 1e-4;

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
