#include "sim/engines/direct/network_model.h"

#include "base/constants.h"
#include "models/scaling.h"
#include "sim/engines/direct/direct_integrators.h"
#include "sim/engines/direct/start_state.h"

namespace metrosync::direct {

NetworkModel::NetworkModel(SplitTimer& timer, const Network& net, RunSink& sink)
    : timer_(timer),
      net_(net),
      sink_(sink),
      eq_(net),
      lay_(eq_.layout()),
      modes_(lay_.platforms, PlatformMode::Stuck),
      rhs_(eq_, modes_),
      tab_(ode::rkTableau(net.sim.integrator.empty() ? defaultDirectIntegrator(net.unionRig())
                                                     : net.sim.integrator)),
      stepper_(tab_, lay_.dim(), rhs_) {
  const ScaledParams sp = computeScaled(net.unionRig());
  period_ = kTwoPi * sp.time_scale_s;
  sample_dt_ = net.sim.sample_s > 0 ? net.sim.sample_s : period_ / 20;
  for (int p = 0; p < lay_.platforms; ++p) {
    const network::Block& b = eq_.block(p);
    contacts_.push_back(b.moves && b.friction.setValued() ? b.friction : PlatformFriction{});
    views_.push_back(std::make_unique<PlatformView>(eq_, modes_, p, rows_));
  }
  scratch_.resize(lay_.dim());
  stepper_.setTolerances(net.sim.accuracy, scaledTolerances(net.sim.accuracy, sp, lay_));
}

std::vector<double> NetworkModel::startState() const {
  std::vector<double> y(lay_.dim(), 0.0);
  for (int p = 0; p < lay_.platforms; ++p) {
    const network::Block& b = eq_.block(p);
    writePlatformStart(net_.platforms[p].rig, b.moves, lay_, p, b.first, y.data());
  }
  return y;
}

// The samples on the grid (simulation.sample) in the current step before t_limit (or at it, if
// inclusive), strictly before t_end: the run's last sample is its final state, at t_end exactly.
void NetworkModel::samplesBefore(Stepper& s, double t_limit, bool inclusive) {
  const double t0 = s.t(), h = s.h();
  for (;;) {
    const double ts = next_sample_ * sample_dt_;
    if (ts >= tEnd() || ts > t_limit || (!inclusive && ts == t_limit)) return;
    s.interpolate(h > 0 ? (ts - t0) / h : 0.0, scratch_.data());
    sample(ts, scratch_.data());
    ++next_sample_;
  }
}

void NetworkModel::sample(double t, const double* y) {
  RecordingScope rec(timer_);
  row_.assign(y, y + lay_.dim());
  sink_.stateSample(t, row_, modes_);
}

}  // namespace metrosync::direct
