// A platform's start state, one construction for a single rig and for each platform of a network
// (issue 24): its x and xdot (when it moves) and its swinging pendulums' angles and rates, written
// into the run's state through the layout's slots, and the resolver of its events armed by the
// start angles. The single rig's layout (models/minimal_equations.h, StateLayout) is a network of
// one's (models/network_equations.h, Layout) but for the ledger: the same slots get the same
// numbers.
#pragma once

#include <vector>

#include "contact/escapement.h"
#include "models/rig.h"
#include "sim/events/resolver.h"

namespace metrosync::direct {

// Writes the start of `rig`'s platform (slots x, v; only when it moves) and of its swinging
// pendulums (locked metronomes take no slot), the first at pendulum index `first` of `lay`.
template <class Layout>
void writePlatformStart(const Rig& rig, bool moves, int x, int v, const Layout& lay, int first,
                        double* y) {
  if (moves) {
    y[x] = rig.platform.start_x_m;
    y[v] = rig.platform.start_v_m_s;
  }
  int j = first;
  for (const MetronomeSpec& m : rig.metronomes) {
    if (m.locked) continue;
    y[lay.theta(j)] = m.start_angle_rad;
    y[lay.omega(j)] = m.start_rate_rad_s;
    ++j;
  }
}

// The resolver of the pendulums [first, first + count) of `lay` (escapement(j): pendulum j's), its
// escapements armed by their angles in the start state y.
template <class Layout, class EscapementOf>
EventResolver startResolver(const Layout& lay, const double* y, int first, int count,
                            EscapementOf&& escapement, const PlatformFriction& friction,
                            double period) {
  std::vector<Escapement> esc;
  std::vector<double> theta0;
  for (int j = first; j < first + count; ++j) {
    esc.push_back(escapement(j));
    theta0.push_back(y[lay.theta(j)]);
  }
  return EventResolver(esc, friction, period, theta0);
}

}  // namespace metrosync::direct
