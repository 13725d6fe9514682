// Doubles as text, the project's two ways (every file, message and report goes through these):
//   roundTripText(v)          the shortest %g text that reads back as exactly v
//   numberText(v, precision)  printf's %.<precision>g (or %e, %f): display and fixed-width columns
// Through std::to_chars, which the standard defines as printf's text, at a fraction of snprintf's
// cost; %g of at most 15 digits through writeGeneral, the same text at a fraction of to_chars'
// cost (trajectory and event rows are the hot spot of a fast run's output).
#pragma once

#include <charconv>
#include <string>

namespace metrosync {

// printf's conversions: %g (general), %e (scientific), %f (fixed)
enum class Notation { General, Scientific, Fixed };

// The most characters writeGeneral writes: a sign, 17 digits, a point and "e-308".
constexpr int kMaxGeneralChars = 32;

// printf("%.<precision>g", v) for a precision of at most 17, written at out (at most
// kMaxGeneralChars characters, no NUL); returns the end. out must have room for kMaxGeneralChars
// characters: those past the returned end may be overwritten (scratch). The same characters as
// std::to_chars(.., chars_format::general, precision), several times faster for the usual
// precisions (base/number_text.cpp).
char* writeGeneral(double v, int precision, char* out);

// printf("%.<precision>g", v) (or %e, %f); NaN as "nan" whatever its sign bit, infinities as
// printf writes them ("inf", "-inf")
inline std::string numberText(double v, int precision = 6, Notation notation = Notation::General) {
  if (v != v) return "nan";
  if (notation == Notation::General && precision <= 17) {
    char buf[kMaxGeneralChars];
    return std::string(buf, writeGeneral(v, precision, buf));
  }
  const std::chars_format f = notation == Notation::General      ? std::chars_format::general
                              : notation == Notation::Scientific ? std::chars_format::scientific
                                                                 : std::chars_format::fixed;
  char buf[352];  // %.<p>f of the largest double: 309 digits, a sign, a point and p decimals
  const auto r = std::to_chars(buf, buf + sizeof buf, v, f, precision);
  return r.ec == std::errc() ? std::string(buf, r.ptr) : std::string("?");
}

// The shortest of printf's %.15g, %.16g, %.17g that reads back as exactly v: "0.3", not
// "0.29999999999999999" (a value the user typed, quoted back or passed on as text)
inline std::string roundTripText(double v) {
  std::string s;
  for (int digits = 15; digits <= 17; ++digits) {
    s = numberText(v, digits);
    double back = 0.0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), back);
    if (r.ec == std::errc() && back == v) break;
  }
  return s;
}

}  // namespace metrosync
