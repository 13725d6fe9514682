// Every value of a sweep axis, listed (tests only: an axis describes its values, sim/analysis/
// sweep.h, and a sweep never lists them).
#pragma once

#include <string>
#include <vector>

#include "sim/analysis/sweep.h"

namespace metrosync::testing_support {

inline std::vector<std::string> axisTexts(const SweepAxis& a) {
  std::vector<std::string> t;
  for (long k = 0; k < a.count; ++k) t.push_back(a.text(k));
  return t;
}

inline std::vector<double> axisValues(const SweepAxis& a) {
  std::vector<double> v;
  for (long k = 0; k < a.count; ++k) v.push_back(a.value(k));
  return v;
}

}  // namespace metrosync::testing_support
