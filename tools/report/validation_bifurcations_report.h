// Part 6 of the validation report (sim/analysis/validation/validation_bifurcations.h): the slow
// flow's located folds and Hopf points for the paper's families, their slow-flow side checks, and
// the full model's brackets of the same transitions; as a report.md section and as summary.json's
// `bifurcations`.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <vector>

#include "sim/analysis/validation/validation_bifurcations.h"

namespace metrosync {

void mdBifurcations(std::ostream& md, const std::vector<BifurcationFamilyResult>& families);
nlohmann::json validationBifurcationsJson(const std::vector<BifurcationFamilyResult>& families);

}  // namespace metrosync
