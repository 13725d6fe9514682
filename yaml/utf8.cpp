#include "yaml/utf8.h"

#include <cstdio>

namespace metrosync {

namespace {

// The length of the well-formed UTF-8 sequence starting at s[i], or 0 (Unicode 15, table 3-7).
std::size_t sequenceLength(const std::string& s, std::size_t i) {
  const auto at = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b0 = at(i);
  if (b0 < 0x80) return 1;
  std::size_t len = 0;
  unsigned char lo = 0x80, hi = 0xBF;  // the allowed range of the second byte
  if (b0 >= 0xC2 && b0 <= 0xDF) {
    len = 2;
  } else if (b0 >= 0xE0 && b0 <= 0xEF) {
    len = 3;
    if (b0 == 0xE0) lo = 0xA0;  // overlong
    if (b0 == 0xED) hi = 0x9F;  // surrogates
  } else if (b0 >= 0xF0 && b0 <= 0xF4) {
    len = 4;
    if (b0 == 0xF0) lo = 0x90;  // overlong
    if (b0 == 0xF4) hi = 0x8F;  // above U+10FFFF
  } else {
    return 0;
  }
  if (i + len > s.size()) return 0;
  if (at(i + 1) < lo || at(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < len; ++k)
    if (at(i + k) < 0x80 || at(i + k) > 0xBF) return 0;
  return len;
}

}  // namespace

std::optional<std::size_t> firstBadUtf8(const std::string& s) {
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t len = sequenceLength(s, i);
    if (len == 0) return i;
    i += len;
  }
  return std::nullopt;
}

bool isControlAt(const std::string& s, std::size_t i) {
  const unsigned char b = static_cast<unsigned char>(s[i]);
  if (b < 0x20 || b == 0x7F) return true;
  const unsigned char next = i + 1 < s.size() ? static_cast<unsigned char>(s[i + 1]) : 0;
  return b == 0xC2 && next >= 0x80 && next <= 0x9F;
}

std::optional<std::size_t> firstControl(const std::string& s) {
  for (std::size_t i = 0; i < s.size(); ++i)
    if (isControlAt(s, i)) return i;
  return std::nullopt;
}

namespace {

// `s` with ill-formed bytes and control characters as \xNN, but for those `keep` accepts.
std::string escaped(const std::string& s, bool (*keep)(unsigned char)) {
  std::string out;
  char buf[16];
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t len = sequenceLength(s, i);
    const unsigned char b = static_cast<unsigned char>(s[i]);
    if (len == 0 || (isControlAt(s, i) && !keep(b))) {
      const std::size_t n = len == 2 ? 2 : 1;  // a C1 character: both its bytes
      for (std::size_t k = 0; k < n; ++k) {
        std::snprintf(buf, sizeof buf, "\\x%02X", static_cast<unsigned char>(s[i + k]));
        out += buf;
      }
      i += n;
    } else {
      out.append(s, i, len);
      i += len;
    }
  }
  return out;
}

}  // namespace

std::string printable(const std::string& s) {
  return escaped(s, [](unsigned char) { return false; });
}

std::string terminalText(const std::string& s) {
  return escaped(s, [](unsigned char b) { return b == '\n' || b == '\t'; });
}

}  // namespace metrosync
