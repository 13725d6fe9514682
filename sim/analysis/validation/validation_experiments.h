// Part 8 of the validation (issue 41): the paper's experiments (section 3C, fig. exp1-exp3) run by
// the full model in each variant of the experiment's rig, each judged against what the paper saw.
//
//   experiments  the four experiment rigs: the two starts (near antiphase, near in phase) at the
//                two measured frictions; exp2 is the low-friction antiphase start (it leaves pi
//                after about 10 s and ends in phase), exp3 the high-friction in-phase start
//                (death a little after 20 s); the other two stay where they start (fig. exp1)
//   variants     the rigs as shipped (I = m L^2, the paper's assumption), and the pendulums'
//                inertia from the measured frequency (section 3D: "around 2.69 Hz"), found by
//                running one metronome alone on a bolted board and scaling I until it ticks at
//                that frequency (docs/experiments.md)
//   the judgement  the final regime as the paper's; for exp2 the time psi leaves antiphase
//                (|psi - pi| > 0.5 rad), for exp3 the time both amplitudes fall below the
//                escapement angle, each within a factor of 2 of the paper's
// Rigs come from the caller (ValidationEngines::load_rig: a shipped rig file with --set keys), so
// that this file needs no loader (includes point down).
#pragma once

#include <string>
#include <vector>

#include "sim/analysis/regime.h"
#include "sim/analysis/validation/validation_catalogue.h"
#include "sim/analysis/validation/validation_progress.h"
#include "sim/analysis/validation/validation_runs.h"

namespace metrosync {

// What the paper measured, for the judgement.
enum class ExperimentClock {
  None,             // the final regime only
  LeavesAntiphase,  // when |psi - pi| first exceeds kLeavesAntiphaseRad
  Dies,             // when both amplitudes fall below theta_c for good
};
constexpr double kLeavesAntiphaseRad = 0.5;

struct ExperimentSpec {
  std::string scenario;  // a shipped scenario (validation_catalogue.h)
  std::string figure;    // "fig. exp2"
  std::string seen;      // what the paper saw, in words
  Regime regime;         // the final regime it saw
  ExperimentClock clock = ExperimentClock::None;
  double seconds = 0.0;  // the clock's time in the experiment (s)
};
const std::vector<ExperimentSpec>& paperExperiments();

struct ExperimentVariant {
  std::string name;               // "as shipped", "measured frequency"
  std::string description;        // for the report
  std::vector<std::string> sets;  // the --set keys that make it from a shipped rig
};

struct ExperimentOutcome {
  std::string scenario, variant;
  ModelRun run;          // the full model over the rig's own duration
  double clock_s = 0.0;  // the measured clock (s); NaN: it never happened
  bool regime_ok = false, clock_ok = false;
  bool reproduces() const { return regime_ok && clock_ok; }
};

struct ExperimentsResult {
  double frequency_hz = 0.0;     // the paper's measured frequency, the variant's target
  double shipped_hz = 0.0;       // what the shipped rig's metronome ticks at alone
  double shipped_inertia = 0.0;  // its inertia (kg m^2)
  double inertia = 0.0;          // the inertia that ticks at frequency_hz (kg m^2)
  double variant_hz = 0.0;       // what that inertia ticks at
  std::vector<ExperimentVariant> variants;
  std::vector<ExperimentOutcome> outcomes;  // experiment-major, variants in order
  std::string failure;  // why the part could not run (the inertia's search failed), or empty
};

// One metronome (the rig's first) alone on a bolted board, the other held in its box: its
// ticking frequency (Hz) from the upward zero crossings of theta between 5 and 20 s. `sets` are
// more --set keys (an inertia). Throws std::runtime_error when the run stops early.
double oneMetronomeFrequency(const ValidationEngines& engines, const std::string& rig_file,
                             std::vector<std::string> sets);

// The inertia (kg m^2, every pendulum the same) at which the first metronome ticks at hz alone
// (oneMetronomeFrequency with `sets`): I scaled by (f / hz)^2 until f is within 1e-4 of hz (at
// most kInertiaIterations more runs).
constexpr int kInertiaIterations = 8;
struct InertiaSearch {
  double start_hz = 0.0;  // the frequency at start_inertia (the search's first run)
  double inertia = 0.0;   // kg m^2
  double hz = 0.0;        // the frequency at that inertia
  int runs = 0;
};
InertiaSearch inertiaForFrequency(const ValidationEngines& engines, const std::string& rig_file,
                                  const std::vector<std::string>& sets, double start_inertia,
                                  double hz);

// The clock of an experiment on a run (seconds; NaN when it never happened).
double experimentClock(const ExperimentSpec& e, const ModelRun& run);
// The judgement of a run against the paper's experiment.
ExperimentOutcome judgeExperiment(const ExperimentSpec& e, const std::string& variant,
                                  ModelRun run);

// Part 8 on the shipped scenarios: the variants, then every experiment in every variant.
ExperimentsResult runExperiments(double frequency_hz, const std::vector<Scenario>& scenarios,
                                 const ValidationEngines& engines, ValidationLog& log, int jobs);

}  // namespace metrosync
