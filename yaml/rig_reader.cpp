#include "yaml/rig_reader.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>

#include "yaml/rig_limits.h"

namespace metrosync::rigfile {

std::optional<double> parseNumber(std::string s) {
  if (!s.empty() && s[0] == '+') s.erase(0, 1);
  std::string low = s;
  for (char& ch : low) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (low == ".inf") return HUGE_VAL;
  if (low == "-.inf") return -HUGE_VAL;
  if (low == ".nan") return std::nan("");
  double v = 0.0;
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(s.data(), end, v);
  if (s.empty() || ptr != end) return std::nullopt;
  // out of double's range: overflow is reported as not finite, underflow as the tiny value
  if (ec == std::errc::result_out_of_range) return std::strtod(s.c_str(), nullptr);
  if (ec != std::errc()) return std::nullopt;
  return v;
}

double positive(const Reader& r, const std::string& key, const std::string& what) {
  const double v = r.number(key, what);
  if (!(v > 0)) r.bad(key, "must be > 0");
  return v;
}
double nonNegative(const Reader& r, const std::string& key, double v) {
  if (!(v >= 0)) r.bad(key, "must be >= 0");
  return v;
}

std::optional<std::string> optName(const Reader& r) {
  const std::optional<std::string> name = r.optText("name");
  if (!name) return name;
  if (name->empty()) r.bad("name", "must not be empty");
  if (name->size() > kMaxNameBytes)
    r.bad("name", "is " + std::to_string(name->size()) + " bytes long (at most " +
                      std::to_string(kMaxNameBytes) + ")");
  if (firstControl(*name))  // C0, DEL and C1 (yaml/utf8.h)
    r.bad("name", "must not contain control characters");
  return name;
}

std::string readName(const Reader& top, const std::string& fallback) {
  const std::optional<std::string> name = optName(top);
  if (!name) return fallback;
  if (name->find_first_of("/\\") != std::string::npos)
    top.bad("name", "must not contain '/' or '\\' (it names the output folder)");
  return *name;
}

}  // namespace metrosync::rigfile
