// Numbers in the report files: text with a given number of significant digits, and JSON numbers
// (JSON has no NaN or infinity: null there).
#pragma once

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace metrosync {

// %.<digits>g; `missing` for NaN and infinities.
inline std::string reportNumber(double v, int digits = 12, const char* missing = "nan") {
  if (!std::isfinite(v)) return missing;
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
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
