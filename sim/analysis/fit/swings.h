// The swings of a measured oscillation (docs/fit.md): where a sampled signal crosses its centre
// (with hysteresis, so that noise near a crossing does not count twice) and how large each
// half-cycle is. The amplitudes come from least-squares fits of a sinusoid at the measured
// frequency over a short window of each half-cycle -- not from the single largest sample, which
// noise biases upwards. Two windows, for the two experiments of the paper's section 3:
//   Peak:     around each extremum, the centre held fixed (a pendulum swings about 0; the window
//             stays clear of the escapement's ticks, which come at theta_c, near the crossings)
//   Crossing: around each crossing, the centre free (a board under Coulomb friction swings about
//             a centre that moves by 2 mu-bar M g / k every half-cycle, eq3.1-eq3.2)
#pragma once

#include <vector>

namespace metrosync {

struct Swing {
  double t_s = 0.0;        // the middle of the window: the extremum (Peak) or the crossing
  double amplitude = 0.0;  // half the peak-to-peak swing, in the signal's unit
  // the amplitude's standard error per unit of the samples' noise (Peak windows; 0 otherwise)
  double error_per_noise = 0.0;
};

struct Swings {
  std::vector<double> crossings_s;   // centre crossings, in time order
  double half_period_s = 0.0;        // least-squares slope of crossing time against index
  double half_period_error_s = 0.0;  // its standard error (0 with fewer than 3 crossings)
  std::vector<Swing> swings;         // one per half-cycle the window fits inside
};

enum class SwingWindow { Peak, Crossing };

// t_s strictly increasing; NaN values are missing samples. Fewer than 2 crossings: no swings.
Swings findSwings(const std::vector<double>& t_s, const std::vector<double>& y, SwingWindow window);

}  // namespace metrosync
