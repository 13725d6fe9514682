// Part 2 of the validation (sim/analysis/validation/validation.h): the paper's statements about
// each of its simulations, checked on the slow flow's run.
#pragma once

#include <string>
#include <vector>

#include "models/scaling.h"
#include "sim/analysis/validation/validation_catalogue.h"
#include "sim/analysis/validation/validation_runs.h"

namespace metrosync {

struct Check {
  std::string what;  // the statement checked
  bool pass = false;
  std::string detail;  // the measured numbers
};

// The paper's statements about a scenario (PaperOutcome) checked on its slow-flow run.
std::vector<Check> paperChecks(PaperOutcome outcome, const ModelRun& slow, const ScaledParams& p);

}  // namespace metrosync
