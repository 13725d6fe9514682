// Validation of the full model against the asymptotics (the slow flow e3.1a-c and its closed
// forms), behind `metrosync validate` and tests/validation. Five parts:
//   1. betas        beta1, beta2 (eq. d2) against the full model's own Coulomb element, driven by
//                   B sin t to its periodic steady state (contact/simbody/driven_coulomb.h)
//   2. scenarios    the paper's eight simulations (section 4) from the slow flow, with the regimes
//                   the paper describes
//   3. convergence  the full model at epsilon = 0.04, 0.02, 0.01 against the slow flow over
//                   tau in [0, 5]: max envelope error and its order in epsilon (theory: 1)
//   4. regimes      the final regime of each scenario from the full model at the rig's epsilon,
//                   0.02 and 0.005 next to the slow flow's: where the asymptotics fail
//   5. sweep        the experiment's regime sequence over mu (figure exp1, right panel)
// Core code: the engines that need Simbody (the full model, the Coulomb-element harness) come in
// as functions and the rigs come in loaded, so that sim/ depends on neither Simbody nor YAML.
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "contact/simbody/driven_coulomb.h"  // the harness's result type (header only)
#include "models/rig.h"
#include "models/scaling.h"
#include "sim/analysis/regime.h"
#include "sim/analysis/validation_bifurcations.h"
#include "sim/analysis/validation_full_orbits.h"
#include "sim/record/envelope.h"
#include "sim/record/run_report.h"

namespace metrosync {

// ---- scenarios --------------------------------------------------------------------------------

// What the paper says the slow flow does in one of its simulations (section 4, text and captions).
enum class PaperOutcome {
  None,                      // not one of the paper's simulations (the experiment's rigs)
  InPhase,                   // f4.1, f4.3 mu = 0.2
  NearAntiphaseOffPi,        // f4.2: locked near pi, not at it (neutral family)
  SuppressionNearAntiphase,  // f4.3 mu = 0.3: one alive, one dead, psi close to pi
  Death,                     // f4.3 mu = 0.4
  LockedFasterLower,         // f4.4 alpha = 0.2: locked near pi, faster metronome (2) lower
  FasterSuppressed,          // f4.4 alpha = 2: metronome 2 (faster) dead, 1 alive, locked near pi
  SuppressionThenDeath,      // f4.4 alpha = 4: 1 suppresses 2 for a long time, then both die
};

// A shipped rig under validation, as listed by shippedScenarios().
struct ScenarioSpec {
  std::string name;         // "f4.3-mu0.3"
  std::string file;         // path under yaml/rigs: "paper/f4.3-mu0.3.yaml"
  double regime_tau = 0.0;  // slow time of the regime runs (part 4): shows the final regime
  PaperOutcome outcome = PaperOutcome::None;
  std::string paper;  // what the paper shows, in words (for the report)
};

// The twelve shipped scenarios: the paper's eight simulations, then the experiment's four rigs.
const std::vector<ScenarioSpec>& shippedScenarios();

// A scenario with its rig loaded.
struct Scenario {
  ScenarioSpec spec;
  ScaledParams scaled;  // computeScaled of the shipped rig (epsilon, tau_end as shipped)
};

// The scenario of that name in `all`; throws std::invalid_argument when there is none.
const Scenario& findScenario(const std::vector<Scenario>& all, const std::string& name);

// The rig with the scaled parameters p (friction, metronomes, start) at another epsilon, run to
// tau_end: the equivalent physical system of rigFromScaled. Throws std::invalid_argument when no
// such system exists.
Rig rigAtEpsilon(const ScaledParams& p, const std::string& name, double epsilon, double tau_end);

// ---- engines ------------------------------------------------------------------------------------

struct ValidationEngines {
  std::function<RunReport(const Rig&, RunSink&)> full_model;        // an Engine's run
  std::function<DrivenCoulombMeasurement(double s)> coulomb_probe;  // measureDrivenCoulomb
};

// ---- one run of either model -------------------------------------------------------------------

struct ModelRun {
  std::string model;  // "full" or "slow"
  double epsilon = 0.0, tau_end = 0.0;
  double mu = 0.0;              // scaled platform friction of the run
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

// The slow flow of p from its start to tau_end, rows on epsilon's grid.
ModelRun runSlowModel(const ScaledParams& p, double epsilon, double tau_end);
// The full model of rigAtEpsilon(p, name, epsilon, tau_end).
ModelRun runFullModelAt(const ValidationEngines& engines, const ScaledParams& p,
                        const std::string& name, double epsilon, double tau_end);

// ---- measures -----------------------------------------------------------------------------------

// Distance between two envelope states in the complex amplitudes of metronome 1's frame,
// w_1 = A_1, w_j = A_j e^{-i psi_j}: max_j |w_j,a - w_j,b|. It weighs a phase error by the
// amplitude, so it stays meaningful where an amplitude is small (a suppressed or dying
// metronome's phase is not).
double envelopeDistance(const EnvelopeRow& a, const EnvelopeRow& b);

struct EnvelopeError {
  double max_distance = 0.0;  // max over rows of envelopeDistance
  double tau_at_max = 0.0;
  double max_dA = 0.0;    // max over rows and metronomes of |dA_i|
  double max_dpsi = 0.0;  // max over rows and j of |wrap(dpsi_j)|, for information
  long rows = 0;          // rows compared
};
// Rows matched on the grid index of epsilon, tau <= tau_max.
EnvelopeError envelopeError(const std::vector<EnvelopeRow>& full,
                            const std::vector<EnvelopeRow>& slow, double epsilon, double tau_max);

// Least-squares slope of log(y) against log(x) (x, y > 0, at least two distinct x).
double fitOrder(const std::vector<double>& x, const std::vector<double>& y);

// ---- checks -------------------------------------------------------------------------------------

struct Check {
  std::string what;  // the statement checked
  bool pass = false;
  std::string detail;  // the measured numbers
};

// The paper's statements about a scenario (PaperOutcome) checked on its slow-flow run.
std::vector<Check> paperChecks(PaperOutcome outcome, const ModelRun& slow, const ScaledParams& p);

// ---- the plan -----------------------------------------------------------------------------------

struct ValidationPlan {
  bool quick = false;
  // part 1
  std::vector<double> beta_s;
  double beta_tol = 1e-7;
  // part 2: every shipped scenario with a PaperOutcome, at its shipped tau
  // part 3
  std::vector<std::string> convergence_scenarios;
  std::vector<double> convergence_eps = {0.04, 0.02, 0.01};
  double convergence_tau = 5.0;
  double order_lo = 0.7, order_hi = 1.3;
  // part 4; epsilon 0 stands for the rig's own epsilon
  std::vector<std::string> regime_scenarios;
  std::vector<double> regime_eps = {0.0, 0.02, 0.005};
  // part 5: the scenario's rig (its own epsilon and tau) with mu replaced
  std::string sweep_scenario = "experiment-low-friction-inphase";
  std::vector<double> sweep_mu;
  // part 6: the slow flow's bifurcations (sim/analysis/validation_bifurcations.h)
  std::vector<BifurcationFamilySpec> bifurcations;
  // part 7: the full model's bifurcations (sim/analysis/validation_full_orbits.h); on in both
  // of defaultValidationPlan's plans
  bool full_orbits = false;
};

// The full plan (`metrosync validate`) or the quick one (`--quick`).
ValidationPlan defaultValidationPlan(bool quick);

// ---- results ------------------------------------------------------------------------------------

struct BetaRow {
  double s = 0.0;
  double beta1_closed = 0.0, beta2_closed = 0.0;
  DrivenCoulombMeasurement measured;
  double err1 = 0.0, err2 = 0.0;  // |measured - closed|
  bool pass = false;
};

struct ScenarioResult {  // part 2
  std::string name;
  ModelRun slow;
  std::vector<Check> checks;
  bool pass = false;
};

struct ConvergenceResult {  // part 3
  std::string name;
  std::vector<double> eps;
  std::vector<EnvelopeError> error;  // per eps
  double order = 0.0;                // fitted on max_distance
  std::vector<int> runs_complete;    // per eps: both models ran to the end (1)
  bool complete = true;
  bool pass = false;
};

struct RegimeComparison {  // part 4
  std::string name;
  double tau_end = 0.0;
  ModelRun slow;                 // at the rig's epsilon
  std::vector<ModelRun> full;    // per plan.regime_eps
  std::vector<double> distance;  // envelopeDistance of the final states, full vs slow
  std::vector<bool> agree;       // same regime (and a settled state within kAgreeDistance)
  // two identical metronomes (same nu, J, theta_c, no detuning): the distance with the full
  // model's metronomes exchanged (NaN otherwise), and whether the states agree that way
  std::vector<double> mirror_distance;
  std::vector<bool> mirror_agree;
};

struct FrictionSweepPoint {  // part 5: one friction value, both models
  double mu = 0.0, mu_bar = 0.0;
  ModelRun slow, full;
};

struct ValidationResults {
  ValidationPlan plan;
  std::vector<BetaRow> betas;
  std::vector<ScenarioResult> scenarios;
  std::vector<ConvergenceResult> convergence;
  std::vector<RegimeComparison> regimes;
  std::string sweep_scenario;
  double sweep_epsilon = 0.0, sweep_tau = 0.0, sweep_psi0 = 0.0;  // of the sweep's base rig
  std::vector<FrictionSweepPoint> sweep;
  std::vector<BifurcationFamilyResult> bifurcations;  // part 6
  std::optional<FullOrbitsResult> full_orbits;        // part 7
  double wall_seconds = 0.0;

  int failedChecks() const;    // betas, paper regimes, convergence orders
  int incompleteRuns() const;  // runs of either model that stopped early
};

// Two final states "agree" when their regimes are the same and, for a settled state with some
// metronome alive (in-phase, antiphase, phase-locked, suppression), their envelopeDistance is at
// most this: well above the O(epsilon) differences of the asymptotics at epsilon <= 0.02, well
// below the distance between qualitatively different states (amplitudes are ~2-4).
constexpr double kAgreeDistance = 0.25;
bool finalStatesAgree(const ModelRun& full, const ModelRun& slow, double distance);

// The envelope state with metronomes 1 and 2 exchanged (N = 2): A = (A_2, A_1), psi = -psi.
EnvelopeRow exchangedPair(const EnvelopeRow& row);
// Two metronomes that differ by nothing but their start (the exchange is a symmetry).
bool identicalPair(const ScaledParams& p);

std::vector<size_t> identity(size_t n);  // 0, 1, .., n - 1

// Runs the plan on the scenarios (which must include every one the plan names). `progress`
// receives one line per run (from one thread at a time). The runs are independent: `jobs`
// threads share them, longest first; the results do not depend on jobs.
ValidationResults runValidation(const ValidationPlan& plan, const std::vector<Scenario>& scenarios,
                                const ValidationEngines& engines,
                                const std::function<void(const std::string&)>& progress = {},
                                int jobs = 1);

}  // namespace metrosync
