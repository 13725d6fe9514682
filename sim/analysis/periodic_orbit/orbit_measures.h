// What a periodic orbit looks like to a reader of the slow flow: each metronome's amplitude and
// the phase differences, averaged over the orbit as envelope.csv averages them over a fast period
// (SPEC 3: A_i = sqrt(theta_i^2 + thetadot_i^2), psi_j = phi_1 - phi_j, phi_i = atan2(theta_i,
// thetadot_i) - t, phases averaged as unit complex numbers), and the events of one period.
// The averages are Gauss-Legendre quadratures on the smooth pieces between the event windows
// (exact to ~1e-12: the integrands jump at ticks, never inside a piece).
#pragma once

#include <vector>

#include "sim/analysis/periodic_orbit/return_map.h"
#include "sim/analysis/periodic_orbit/shooting.h"

namespace metrosync::orbit {

// The events of one period (its windows), counted as the engine's RunCounts count them.
struct EventCounts {
  std::vector<int> ticks;  // (N x 1) per rig metronome
  // the platform's switches of its own (its velocity reaching 0, its holding force the bound)
  int stick_slip = 0;  // between stuck and slipping
  int reversals = 0;   // slip+ <-> slip- without sticking
  int at_ticks = 0;    // switches made by a tick's impulse (unsticking, reversing, stopping)
  bool operator==(const EventCounts& o) const {
    return ticks == o.ticks && stick_slip == o.stick_slip && reversals == o.reversals &&
           at_ticks == o.at_ticks;
  }
  bool operator!=(const EventCounts& o) const { return !(*this == o); }
};

EventCounts countEvents(const ReturnMap& map, const Pass& pass);

struct OrbitMeasures {
  std::vector<double> A;    // (N x 1), rig order; 0 for a locked metronome
  std::vector<double> psi;  // (N - 1 x 1): psi_j, j = 2..N, in [-pi/2, 3 pi/2)
  EventCounts events;
};

OrbitMeasures measureOrbit(const ReturnMap& map, const Orbit& orbit);

}  // namespace metrosync::orbit
