// A platform's start state, one construction for a single rig and for each platform of a network
// (issue 24): its x and xdot (when it moves) and its swinging pendulums' angles and rates, written
// into the run's state through the layout's slots, the resolver of its events armed by the start
// angles, and the state's error targets, in the one layout (models/network_layout.h).
#pragma once

#include <vector>

#include "contact/escapement.h"
#include "models/network_layout.h"
#include "models/rig.h"
#include "models/scaling.h"
#include "sim/events/resolver.h"

namespace metrosync::direct {

// Writes the start of `rig`'s platform (platform p of `lay`; only when it moves) and of its
// swinging pendulums (locked metronomes take no slot), the first at pendulum index `first`.
inline void writePlatformStart(const Rig& rig, bool moves, const network::Layout& lay, int p,
                               int first, double* y) {
  if (moves) {
    y[lay.x(p)] = rig.platform.start_x_m;
    y[lay.v(p)] = rig.platform.start_v_m_s;
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
template <class EscapementOf>
EventResolver startResolver(const network::Layout& lay, const double* y, int first, int count,
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

// The absolute error targets of the state (the relative one is `accuracy`): errors in the scaled
// variables' units (s2.1), angles in units of sqrt(eps), every platform in units of
// I1 eps^{3/2} / (m1 L1), time in 1/omega0; the ledger's quadratures are not controlled (-1:
// nothing depends on them).
inline std::vector<double> scaledTolerances(double accuracy, const ScaledParams& sp,
                                            const network::Layout& lay) {
  const double omega0 = 1.0 / sp.time_scale_s;
  std::vector<double> atol(lay.dim(), -1.0);
  for (int p = 0; p < lay.platforms; ++p) {
    atol[lay.x(p)] = accuracy * sp.x_scale_m;
    atol[lay.v(p)] = accuracy * sp.x_scale_m * omega0;
  }
  for (int j = 0; j < lay.n; ++j) {
    atol[lay.theta(j)] = accuracy * sp.angle_scale;
    atol[lay.omega(j)] = accuracy * sp.angle_scale * omega0;
  }
  return atol;
}

}  // namespace metrosync::direct
