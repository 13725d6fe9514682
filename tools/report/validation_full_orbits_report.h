// Part 7 of the validation report (sim/analysis/validation/validation_full_orbits.h): the full
// model's bifurcations on its periodic orbits at several epsilon beside the slow flow's, with the
// fitted order, and the default rig's asymmetric state; as a report.md section, its summary row,
// and summary.json's `full_orbits`.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>

#include "sim/analysis/validation/validation_full_orbits.h"

namespace metrosync {

// "| 7. ... | ... |" for the summary table.
void mdFullOrbitsSummaryRow(std::ostream& md, const FullOrbitsResult& r);
void mdFullOrbits(std::ostream& md, const FullOrbitsResult& r);
nlohmann::json validationFullOrbitsJson(const FullOrbitsResult& r);

}  // namespace metrosync
