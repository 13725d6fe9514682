// What a fit compares (docs/fit.md): the observations taken from a data file and the noise of
// each measured quantity.
//   full model: every sample at t >= 0 of every column (theta_i in rad, x in m)
//   slow flow: the swings' amplitudes of every theta column (one per half-cycle, swings.h); x is
//     not a slow-flow quantity and is left out (a warning)
// The noise of a column is --noise where given (the angles', or x's when x is all there is), else
// estimated from the data's high-frequency part (noise_level.h); an amplitude's noise is the
// samples' carried through its window's fit.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sim/analysis/fit/data_file.h"
#include "sim/analysis/fit/fit_problem.h"

namespace metrosync {

struct FitData {
  std::vector<std::string> quantity_names;  // the data's column names, in header order
  std::vector<int> metronome;               // per quantity: theta_{i+1} -> i, x -> -1
  std::vector<Observation> observations;    // in time order
  std::vector<double> noise;                // per quantity, in its unit (0: unknown)
  bool noise_reliable = false;              // every quantity's noise given or well estimated
  std::string noise_from;                   // "--noise", "data", "data (upper bound)", "unknown"
  std::vector<std::string> warnings;        // for the user (columns not used, ...)
};

// theta_c_rad per metronome (where the escapement ticks: no noise window spans one). Throws
// std::invalid_argument when nothing is left to fit.
FitData fitData(const MeasuredData& data, bool slow, const std::vector<double>& theta_c_rad,
                std::optional<double> noise);

}  // namespace metrosync
