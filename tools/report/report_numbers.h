// Numbers in the report files: table cells with a text for missing values, and JSON numbers
// (JSON has no NaN or infinity: null there).
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/number_text.h"

namespace metrosync {

// A cell of a report's table or data file: numberText (base/number_text.h) with `missing` for NaN
// and infinities.
inline std::string reportNumber(double v, int digits = 12, const char* missing = "nan") {
  return std::isfinite(v) ? numberText(v, digits) : std::string(missing);
}

// A CSV cell that may have no value (issue 39): NaN, the producers' "no value", is an empty cell;
// every other number is written, an infinity too, for the writers' check to refuse
// (sim/record/finite_check.h).
inline std::string optionalCell(double v, int digits = 12) {
  return std::isnan(v) ? std::string() : numberText(v, digits);
}

inline nlohmann::json jsonNumber(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

inline nlohmann::json jsonNumbers(const std::vector<double>& v) {
  nlohmann::json j = nlohmann::json::array();
  for (double x : v) j.push_back(jsonNumber(x));
  return j;
}

}  // namespace metrosync
