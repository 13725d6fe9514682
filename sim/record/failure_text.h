// A failed run's message, one form on every engine and for every rig (RunReport::failure,
// summary.json `failure`): "simulation failed at t = T: why", T in the run's own time unit. A
// single rig gives its scales: seconds ("T s") or, for a scaled rig, scaled time, and its slow time
// "(tau = ...)"; a network of several platforms has no one slow time: seconds.
#pragma once

#include <string>

#include "base/number_text.h"
#include "models/scaling.h"

namespace metrosync {

// t_s: the time of the failure in seconds; `sp`: a single rig's scales (nullptr: a network's
// run), `scaled`: the rig is written in scaled units.
inline std::string failureText(double t_s, const std::string& why, const ScaledParams* sp = nullptr,
                               bool scaled = false) {
  std::string when = numberText(t_s) + " s";
  if (sp) {
    const double omega0 = 1.0 / sp->time_scale_s;
    when = numberText(scaled ? t_s * omega0 : t_s) + (scaled ? "" : " s") +
           " (tau = " + numberText(sp->epsilon * omega0 * t_s) + ")";
  }
  return "simulation failed at t = " + when + ": " + why;
}

}  // namespace metrosync
