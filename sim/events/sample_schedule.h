// When trajectory rows and envelope samples are taken: rows every `row_dt` (simulation.sample,
// default period/20) and envelope samples every period/64, both strictly before t_end (the run's
// last state is recorded by the run itself). The engines take samples from their interpolants: a
// sample never forces the integrator to stop. The direct engine schedules rows only (its envelope
// integrates each step's interpolant: sim/record/envelope_quadrature.h); the Simbody engine keeps
// both kinds as its report times, which bound its steps, so that its runs are stepped as before
// (its envelope too comes from the steps' interpolants).
#pragma once

#include <algorithm>
#include <limits>

namespace metrosync {

class SampleSchedule {
 public:
  static constexpr int kEnvelopeSamplesPerPeriod = 64;
  static constexpr int kRowsPerPeriodByDefault = 20;

  // sample: the rig's row interval (<= 0: the default); period: the fast period; both in the
  // engine's time unit. rows / envelope: false when the sink takes none of that kind
  // (RunSink::wantsTrajectory, wantsEnvelope): none are scheduled.
  SampleSchedule(double sample, double period, double t_end, bool rows = true, bool envelope = true)
      : row_dt_(sample > 0 ? sample : period / kRowsPerPeriodByDefault),
        env_dt_(period / kEnvelopeSamplesPerPeriod),
        t_end_(t_end),
        rows_(rows),
        envelope_(envelope) {}

  // The next sample time, or t_end when none is left before it.
  double next() const { return std::min({nextRow(), nextEnvelope(), t_end_}); }

  // Calls take(t, row, envelope) for every sample due before t_limit (or at it, if inclusive),
  // in time order; row / envelope say which of the two is due at t.
  template <class Take>
  void takeDue(double t_limit, bool inclusive, Take&& take) {
    while (true) {
      const double ts = std::min(nextRow(), nextEnvelope());
      if (!(ts < t_end_ && (ts < t_limit || (inclusive && ts == t_limit)))) return;
      const bool row = nextRow() <= ts, env = nextEnvelope() <= ts;
      take(ts, row, env);
      k_row_ += row;
      k_env_ += env;
    }
  }

 private:
  double nextRow() const { return rows_ ? static_cast<double>(k_row_) * row_dt_ : kNever; }
  double nextEnvelope() const { return envelope_ ? static_cast<double>(k_env_) * env_dt_ : kNever; }
  static constexpr double kNever = std::numeric_limits<double>::infinity();

  double row_dt_, env_dt_, t_end_;
  bool rows_, envelope_;
  long k_row_ = 1, k_env_ = 1;  // the samples at t = 0 are the run's first state
};

}  // namespace metrosync
