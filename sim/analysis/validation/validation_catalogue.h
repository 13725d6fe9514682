// The validation's catalogue (`metrosync validate`, sim/analysis/validation/validation.h): the
// shipped rigs it runs, what the paper says each of the paper's simulations shows, and a scenario's
// rig at another epsilon.
#pragma once

#include <string>
#include <vector>

#include "models/rig.h"
#include "models/scaling.h"

namespace metrosync {

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

}  // namespace metrosync
