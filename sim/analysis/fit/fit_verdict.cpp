#include "sim/analysis/fit/fit_verdict.h"

#include <cmath>
#include <cstdio>

#include "base/number_text.h"

namespace metrosync {

namespace {

// "theta_1 0.0275 against 0.0015" for the quantities above their noise level
std::string above(const FitOutcome& out) {
  std::string s;
  for (std::size_t q = 0; q < out.quantity_names.size(); ++q) {
    const double n = out.noise_by_quantity[q], r = out.rms_by_quantity[q];
    if (n > 0 && !(r <= kNoiseTolerance * n))
      s += (s.empty() ? "" : ", ") + out.quantity_names[q] + " " + numberText(r, 3) + " against " +
           numberText(n, 3);
  }
  return s;
}

}  // namespace

bool atNoiseLevel(const std::vector<double>& rms, const std::vector<double>& noise) {
  bool any = false;
  for (std::size_t q = 0; q < rms.size(); ++q) {
    if (!(noise[q] > 0)) continue;
    any = true;
    if (!(rms[q] <= kNoiseTolerance * noise[q])) return false;
  }
  return any;
}

void judgeFit(FitOutcome& out, bool noise_reliable, bool slow) {
  const bool at_noise = atNoiseLevel(out.rms_by_quantity, out.noise_by_quantity);
  if (!out.solver_converged) {
    out.converged = false;
    out.note = "the solver stopped before converging (" + out.solver_summary + ")";
  } else if (noise_reliable && at_noise) {
    out.converged = true;
    out.note = "the residual is at the noise level of every column";
  } else if (noise_reliable || (!at_noise && !above(out).empty())) {
    out.converged = false;
    out.note = "the residual is above the noise level (" + above(out) + "): " +
               (slow ? "the slow flow is an asymptotic model (O(epsilon) off the full model), "
                       "or "
                     : "") +
               "a wrong optimum, a wrong rig (a key that should be free is not), or data the "
               "model cannot describe";
  } else {
    out.converged = true;
    out.note = "the noise level is not known (" + out.noise_from +
               "): the residual was not checked against it; give --noise";
  }
  if (std::isfinite(out.smooth_until_s))
    out.note +=
        "; the model is smooth in the keys only up to t = " + numberText(out.smooth_until_s, 3) +
        " s (an escapement ticking at grazing, or a late phase so sensitive to the keys "
        "that the fit has local optima close together): the standard errors come from "
        "the record up to then and are upper bounds";
}

}  // namespace metrosync
