// Numbers in messages and reports of the periodic-orbit analysis: %.<digits>g.
#pragma once

#include <cstdio>
#include <string>

namespace metrosync::orbit {

inline std::string numberText(double v, int digits = 6) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

}  // namespace metrosync::orbit
