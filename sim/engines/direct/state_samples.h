// A network's recording in the direct model (direct_model.h): its whole state on the sample grid
// (simulation.sample, or a twentieth of the fast period) for the sink (RunSink::stateSample), the
// last at t_end exactly. A network counts as its events the windows and every row the resolvers
// would write (as the Simbody engine's network recorder does).
#pragma once

#include <vector>

#include "sim/record/run_report.h"
#include "sim/record/split_timer.h"

namespace metrosync::direct {

class StateSamples {
 public:
  using Modes = std::vector<PlatformMode>;
  StateSamples(SplitTimer& timer, RunSink& sink, double sample_s, double period, double t_end,
               int dim)
      : timer_(timer),
        sink_(sink),
        sample_dt_(sample_s > 0 ? sample_s : period / 20),
        t_end_(t_end),
        scratch_(dim) {}

  void start(const double* y, const Modes& m) {
    sample(0.0, y, m);
    next_sample_ = 1;
  }
  // The samples on the grid in the current step before t_limit (or at it, if inclusive), strictly
  // before t_end: the run's last sample is its final state, at t_end exactly.
  template <class Stepper>
  void samplesBefore(Stepper& s, double t_limit, bool inclusive, const Modes& m) {
    const double t0 = s.t(), h = s.h();
    for (;;) {
      const double ts = next_sample_ * sample_dt_;
      if (ts >= t_end_ || ts > t_limit || (!inclusive && ts == t_limit)) return;
      s.interpolate(h > 0 ? (ts - t0) / h : 0.0, scratch_.data());
      sample(ts, scratch_.data(), m);
      ++next_sample_;
    }
  }
  void last(const double* y, double t, const Modes& m, RunReport&) { sample(t, y, m); }
  void close(RunReport& r) const { r.counts.events += rows_; }
  void eventRow(const char*, const double*, double, PlatformMode) { ++rows_; }
  void snapshot(const double*, double, PlatformMode) {}
  void eventRecord(const char*, int, const double*, double, PlatformMode) {}

 private:
  void sample(double t, const double* y, const Modes& m) {
    RecordingScope rec(timer_);
    row_.assign(y, y + scratch_.size());
    sink_.stateSample(t, row_, m);
  }

  SplitTimer& timer_;
  RunSink& sink_;
  double sample_dt_, t_end_;
  std::vector<double> scratch_, row_;
  long next_sample_ = 0;
  long rows_ = 0;  // the event rows of every window
};

}  // namespace metrosync::direct
