// The JSON files of every command (summary.json, sweep.json, basin.json, fit.json, ...), written
// through one function that first checks the tree: nlohmann writes a NaN or an infinity as null,
// so a non-finite number would pass for "no value" (issue 39). A value that is absent on purpose
// is null in the tree already (jsonNumber, tools/report/report_numbers.h).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace metrosync {

// Throws NonFiniteOutput (sim/record/finite_check.h) naming `file` and the value's place (a JSON
// pointer, e.g. /final/A/1) when a number of `j` is not finite.
void checkFiniteJson(const std::string& file, const nlohmann::json& j);

// `j` checked, then dumped with two spaces and a newline, written atomically to `path`.
void writeJsonFile(const std::string& path, const nlohmann::json& j);

// `j` with every non-finite number made null: the summary of a run that failed (exit 3 already),
// which keeps what it has where the run stopped.
nlohmann::json nullingNonFinite(nlohmann::json j);

}  // namespace metrosync
