#include "tools/report/json_file.h"

#include <cmath>

#include "base/number_text.h"
#include "sim/record/atomic_file.h"
#include "sim/record/finite_check.h"

namespace metrosync {

namespace {

// A key as a JSON pointer's reference token (RFC 6901): ~ as ~0, / as ~1.
std::string pointerToken(const std::string& key) {
  std::string t;
  for (char c : key)
    t += c == '~' ? std::string("~0") : c == '/' ? std::string("~1") : std::string(1, c);
  return t;
}

void checkAt(const std::string& file, const nlohmann::json& j, const std::string& where) {
  if (j.is_number_float()) {
    const double v = j.get<double>();
    if (!std::isfinite(v))
      throw NonFiniteOutput(file + ": " + (where.empty() ? "/" : where) + " = " + numberText(v) +
                            " is not a finite number (a value left out is null)");
  } else if (j.is_object()) {
    for (const auto& [key, value] : j.items())
      checkAt(file, value, where + "/" + pointerToken(key));
  } else if (j.is_array()) {
    for (std::size_t k = 0; k < j.size(); ++k) checkAt(file, j[k], where + "/" + std::to_string(k));
  }
}

}  // namespace

void checkFiniteJson(const std::string& file, const nlohmann::json& j) {
  checkAt(file, j, "");
}

nlohmann::json nullingNonFinite(nlohmann::json j) {
  if (j.is_number_float() && !std::isfinite(j.get<double>())) return nullptr;
  if (j.is_structured())
    for (auto& v : j) v = nullingNonFinite(std::move(v));
  return j;
}

void writeJsonFile(const std::string& path, const nlohmann::json& j) {
  checkFiniteJson(path, j);
  writeFileAtomically(path, j.dump(2) + "\n");
}

}  // namespace metrosync
