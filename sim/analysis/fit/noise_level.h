// The noise of a measured column from the data's high-frequency part (docs/fit.md): the residual
// of a local quartic fitted to each 7 consecutive samples, at the middle sample, divided by its
// standard deviation for unit white noise (sqrt(1 - h), h the fit's leverage there), and the
// median absolute residual scaled to a Gaussian's sigma. Windows that hold an escapement tick (a
// kink in theta, and in x) are skipped: the pendulum's smooth swing between ticks is a quartic to
// ~1e-5 rad at 30 samples per period, far below a camera's noise. A second estimate over 9
// samples checks that: when the two disagree, the signal, not the noise, fills the windows (a
// record sampled too coarsely) and the estimate is only an upper bound. So is the estimate from
// every window, ticks and all, when too few are free of them (ticks every few samples).
#pragma once

#include <vector>

#include "sim/analysis/fit/data_file.h"

namespace metrosync {

struct NoiseEstimate {
  double sigma = 0.0;     // in the column's unit; 0 when there were too few windows
  bool reliable = false;  // the two window sizes agree (see above)
  int windows = 0;        // windows used
};

// `ticks`: one flag per row of `data`, true when an escapement tick may lie between this row and
// the next (escapementTicks below).
NoiseEstimate estimateNoise(const MeasuredData& data, const DataColumn& column,
                            const std::vector<bool>& ticks);

// Rows after which an angle column passes +-theta_c moving outwards (where the escapement ticks),
// from every theta column; theta_c_rad per metronome.
std::vector<bool> escapementTicks(const MeasuredData& data, const std::vector<double>& theta_c_rad);

}  // namespace metrosync
