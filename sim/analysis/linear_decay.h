// The paper's section 3A experiment (eq3.1-eq3.2): the metronomes locked, the board on springs,
// rolling (Coulomb) friction. Between two extremes the board moves as a harmonic oscillator about
// a shifted centre, so the amplitude falls by 2 mu-bar M g / kappa every half period: the
// extremes |x| lie on a straight line of slope
//     slope = 4 mu-bar M g / (T kappa) = mu-bar T g / pi^2,    T = 2 pi sqrt(M / kappa),
// and the slope measured on a run gives back the mu-bar that made it (the paper's method). The
// extremes are the platform's stops: the states of its stick and slip events (events.csv).
#pragma once

#include <optional>
#include <vector>

#include "models/rig.h"

namespace metrosync {

// A physical rig with every metronome locked, a spring to ground and Coulomb friction.
bool isSection3ARig(const Rig& rig);

struct Section3AResult {
  double slope_m_s = 0.0;  // decay of the amplitude |x| of the extremes, least squares, > 0
  double mu_bar = 0.0;     // the mu-bar the slope implies: slope pi^2 / (T g)
  double period_s = 0.0;   // T = 2 pi sqrt(M / kappa)
  int extremes = 0;        // the points fitted
};

class LinearDecay {
 public:
  // One extreme of the board: time (s) and position (m) when it stopped.
  void addExtreme(double t_s, double x_m);
  // The fit over the extremes; nullopt with fewer than 3 (the slope needs two, a check one more).
  std::optional<Section3AResult> result(const Rig& rig) const;

 private:
  std::vector<double> t_, a_;
};

}  // namespace metrosync
