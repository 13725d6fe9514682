// One run of either model for the validation (sim/analysis/validation/validation.h): the slow flow,
// or the full model through the engine the caller passes in (sim/ sees no Simbody), each kept as
// its envelope rows, regime verdict and the platform's state over the regime window.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "contact/simbody/driven_coulomb.h"  // the harness's result type (header only)
#include "models/rig.h"
#include "models/scaling.h"
#include "sim/analysis/regime.h"
#include "sim/record/envelope.h"
#include "sim/record/run_report.h"

namespace metrosync {

// The engines that need Simbody, as functions (tools/cli/validate.cpp passes them in).
struct ValidationEngines {
  std::function<RunReport(const Rig&, RunSink&)> full_model;        // an Engine's run
  std::function<DrivenCoulombMeasurement(double s)> coulomb_probe;  // measureDrivenCoulomb
  // a shipped rig (its path under the rigs' folder) with --set keys applied: part 8's variants
  std::function<Rig(const std::string& file, const std::vector<std::string>& sets)> load_rig;
};

struct ModelRun {
  std::string model;  // "full" or "slow"
  double epsilon = 0.0, tau_end = 0.0;
  double mu = 0.0;              // scaled platform friction of the run
  double time_scale_s = 0.0;    // seconds per unit of scaled time of the rig it stands for
  std::vector<double> theta_c;  // (N x 1) scaled critical angles
  RunReport report;
  RegimeVerdict verdict;              // Regime::Unknown when the run did not complete
  std::vector<EnvelopeRow> envelope;  // every row, one per fast period
  // the platform over the regime window (last 10% in tau): the full model's share of trajectory
  // rows with the platform stuck; the slow flow's Coulomb regime at the final drive s = |Z| / mu
  double platform_stuck_fraction = std::numeric_limits<double>::quiet_NaN();
  std::string platform;  // "stuck", "stick-slip", "slipping" (empty: no Coulomb platform)
  const EnvelopeRow& final() const { return report.final_row; }
};

// A run's label in part 5's regime sequence (and the report's): "failed" when it stopped early,
// else its regime's name, with ", uncoupled" for an alive state over a platform at rest.
std::string sweepLabel(const ModelRun& run);

// The slow flow of p from its start to tau_end, rows on epsilon's grid.
ModelRun runSlowModel(const ScaledParams& p, double epsilon, double tau_end);
// The full model of rigAtEpsilon(p, name, epsilon, tau_end).
ModelRun runFullModelAt(const ValidationEngines& engines, const ScaledParams& p,
                        const std::string& name, double epsilon, double tau_end);

}  // namespace metrosync
