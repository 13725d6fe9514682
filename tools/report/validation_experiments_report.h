// Part 8 of the validation report (sim/analysis/validation/validation_experiments.h): the paper's
// experiments in each variant of the rig, what the paper saw against what the full model does, and
// which variant reproduces what; as a report.md section, its summary row and summary.json's
// `experiments`.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>

#include "sim/analysis/validation/validation_experiments.h"

namespace metrosync {

// "| 8. ... | ... |" for the summary table.
void mdExperimentsSummaryRow(std::ostream& md, const ExperimentsResult& r);
void mdExperiments(std::ostream& md, const ExperimentsResult& r);
nlohmann::json validationExperimentsJson(const ExperimentsResult& r);

}  // namespace metrosync
