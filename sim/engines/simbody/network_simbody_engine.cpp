// The Simbody engine's entry for a network of platforms: the network's system
// (models/simbody/platform_system.h), run by the one run loop (platform_run.h), its samples in the
// network's form (network::Layout) at simulation.sample (default period/20), then its final state.
#include "sim/engines/simbody/network_simbody_engine.h"

#include <string>

#include "base/constants.h"
#include "models/scaling.h"
#include "models/simbody/platform_system.h"
#include "sim/engines/simbody/platform_run.h"
#include "sim/engines/simbody/simbody_engine.h"

namespace metrosync {

namespace {

class NetworkRecorder : public RunRecorder {
 public:
  NetworkRecorder(const PlatformSystem& ps, NetworkSink& sink) : ps_(ps), sink_(sink) {}
  const std::vector<double>& finalState() const { return y_; }

  double sampleInterval() const override { return ps_.network().sim.sample_s; }
  void sample(const SimTK::State& s, double t, bool row, bool) override {
    if (!row) return;
    ps_.layoutState(s, y_);
    modes_.assign(ps_.numPlatforms(), PlatformMode::Stuck);
    for (int p = 0; p < ps_.numPlatforms(); ++p)
      if (ps_.contact(p)) modes_[p] = ps_.contact(p)->mode(s);
    sink_.sample(t, y_, modes_);
  }
  // the last sample: the final state (the schedule's samples stop short of the end)
  void finish(const SimTK::State& s) override { sample(s, s.getTime(), true, false); }
  std::string failureText(double t, const std::string& why) const override {
    return "at t = " + std::to_string(t) + " s: " + why;
  }

 private:
  const PlatformSystem& ps_;
  NetworkSink& sink_;
  std::vector<double> y_;
  std::vector<PlatformMode> modes_;
};

}  // namespace

RunReport runNetworkSimbody(const Network& net, NetworkSink& sink) {
  const double time_scale = computeScaled(net.unionRig()).time_scale_s;
  PlatformSystem ps(net);
  RunReport report;
  report.model = "full";
  report.engine = "simbody";
  report.accuracy = net.sim.accuracy;
  report.has_ledger = true;
  report.integrator =
      net.sim.integrator.empty() ? simbodyIntegratorNames().front() : net.sim.integrator;
  report.fast_period_s = kTwoPi * time_scale;
  NetworkRecorder recorder(ps, sink);
  const PlatformRunResult r = runPlatforms(ps, report.integrator, time_scale, recorder);
  report.complete = r.complete;
  report.failure = r.failure;
  report.counts = r.counts;
  // a network report's events: its windows and its event rows (as the direct network engine's)
  report.counts.events = r.counts.events + r.forced_stops + r.event_rows;
  report.ledger = r.ledger;
  report.t_end = r.t_end;
  report.final_state = recorder.finalState();
  report.wall_seconds = r.wall_seconds;
  report.engine_seconds = r.engine_seconds;
  return report;
}

}  // namespace metrosync
