#include "sim/analysis/fit/model_jacobian.h"

#include "base/constants.h"
#include "models/network_layout.h"
#include "models/scaling.h"
#include "sim/analysis/fit/key_directions.h"
#include "sim/analysis/fit/trajectory_sensitivity.h"
#include "sim/engines/direct/start_state.h"

namespace metrosync {

namespace {

// The error targets of the state the engine ran at: its accuracy, its absolute targets in the
// scaled variables' units (start_state.h), steps at most a tenth of the fast period.
SensitivitySettings settingsOf(const Rig& rig, const orbit::PhysicalModel& m) {
  const ScaledParams sp = computeScaled(rig);
  network::Layout lay;  // a single board: one platform, no damper
  lay.platforms = 1;
  lay.n = m.n();
  SensitivitySettings s;
  s.accuracy = rig.sim.accuracy;
  s.atol = direct::scaledTolerances(rig.sim.accuracy, sp, lay);
  s.atol.resize(m.dim());  // without the ledger's quadratures
  s.max_step_s = 0.1 * kTwoPi * sp.time_scale_s;
  return s;
}

// The state component each observation reads: theta of its pendulum, x; -1 for a locked
// metronome's angle (it does not move).
std::vector<int> componentsOf(const orbit::PhysicalModel& m, const FitData& d, int n) {
  std::vector<int> swinging(d.metronome.size(), -1);
  for (std::size_t q = 0; q < d.metronome.size(); ++q) {
    if (d.metronome[q] < 0) swinging[q] = orbit::PhysicalModel::kX;
    for (int j = 0; j < m.n(); ++j)
      if (m.rigIndex(j) == d.metronome[q]) swinging[q] = m.theta(j);
  }
  std::vector<int> c(n);
  for (int i = 0; i < n; ++i) c[i] = swinging[d.observations[i].quantity];
  return c;
}

}  // namespace

bool hasModelJacobian(const FitProblem& p, const Rig& rig) {
  return p.settings.model == "full" && orbit::PhysicalModel(rig).hasParameterDerivatives();
}

orbit::Mat modelJacobian(const FitProblem& p, const std::vector<double>& values,
                         const ModelTrajectory& run, const FitData& data, int n,
                         const std::vector<bool>& wanted) {
  const orbit::PhysicalModel model(run.rig());
  const orbit::Mat dirs = keyDirections(p, values, wanted, model);
  const orbit::EngineTrace trace =
      orbit::traceOfRecords(model, run.events(), run.rig().platform.start_v_m_s);
  std::vector<double> times(n);
  for (int i = 0; i < n; ++i) times[i] = data.observations[i].t_s;
  return trajectorySensitivities(model, trace, dirs, times, componentsOf(model, data, n),
                                 settingsOf(run.rig(), model));
}

}  // namespace metrosync
