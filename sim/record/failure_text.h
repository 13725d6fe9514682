// A failed run's message, one form on every engine (RunReport::failure, summary.json `failure`):
// "simulation failed at t = T: why", T in the run's own time unit. A single rig: seconds ("T s")
// or, for a scaled rig, scaled time, and its slow time "(tau = ...)"; a network: seconds.
#pragma once

#include <string>

#include "base/number_text.h"
#include "models/scaling.h"

namespace metrosync {

// t_s: the time of the failure in seconds.
inline std::string rigFailureText(double t_s, const ScaledParams& sp, bool scaled,
                                  const std::string& why) {
  const double omega0 = 1.0 / sp.time_scale_s;
  return "simulation failed at t = " + numberText(scaled ? t_s * omega0 : t_s) +
         (scaled ? "" : " s") + " (tau = " + numberText(sp.epsilon * omega0 * t_s) + "): " + why;
}

inline std::string networkFailureText(double t_s, const std::string& why) {
  return "simulation failed at t = " + numberText(t_s) + " s: " + why;
}

}  // namespace metrosync
