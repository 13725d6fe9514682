// The one event-storm (Zeno) rule of every engine: more than `max_events` discontinuities (event
// windows, plastic stops, redone steps) while time advances by less than `window` fast periods
// ends the run, incomplete. A physical event sequence needs time to advance (a tick per half
// period, a few switches per tick): a thousand in a millionth of a period is an accumulation
// point of events that no integrator can pass. A second, sustained tier catches a storm that an
// integrator resolves too coarsely for the first (below).
#pragma once

#include <string>

namespace metrosync {

class StormGuard {
 public:
  static constexpr long kMaxEvents = 1000;
  static constexpr double kWindowPeriods = 1e-6;
  // The sustained tier. Simbody's steps around the 1.6 GHz ringing of yaml/rigs/hard/storm.yaml
  // come ~5e-10 s apart: about 600 windows per millionth of a period, never 1000, so the first
  // tier never trips while the run crawls through 10^6 reversals. Twenty thousand discontinuities
  // within a ten-thousandth of a period is still four orders of magnitude above any physical
  // sequence (a few per half period per metronome) and trips such a storm after seconds of CPU.
  static constexpr long kSustainedEvents = 20000;
  static constexpr double kSustainedWindowPeriods = 1e-4;

  // period: the fast period in the engine's time unit; the first tier's limits may be changed
  // (tests), the sustained tier's are fixed
  explicit StormGuard(double period, long max_events = kMaxEvents,
                      double window_periods = kWindowPeriods)
      : burst_{max_events, window_periods, window_periods * period},
        sustained_{kSustainedEvents, kSustainedWindowPeriods, kSustainedWindowPeriods * period} {}

  // Notes a discontinuity at t; true once either tier is met (the run must stop).
  bool note(double t) {
    const bool burst = burst_.note(t);
    const bool sustained = sustained_.note(t);
    if (!tripped_) tripped_ = burst ? &burst_ : sustained ? &sustained_ : nullptr;
    return tripped_ != nullptr;
  }

  // The failure message (of the tier that tripped).
  std::string why() const;

 private:
  // more than `max_events` while time advances by less than `window`
  struct Tier {
    long max_events;
    double window_periods;
    double window;  // in the engine's time unit
    double start = -1e300;
    long count = 0;
    bool note(double t) {
      if (t - start > window) {
        start = t;
        count = 0;
      }
      return ++count > max_events;
    }
  };
  Tier burst_, sustained_;
  const Tier* tripped_ = nullptr;
};

}  // namespace metrosync
