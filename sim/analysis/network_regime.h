// The label of a network's state (docs/networks.md), judged on the groups' (platforms') order
// parameters over the last tenth of the run (RegimeRules::window_fraction, at least
// RegimeRules::min_periods fast periods: the single-platform classifier's window). With r_g the
// mean of group g's r over the window and dPhi_g the unwrapped Phi_g - Phi_1 (group 1 the
// reference), rules in order:
//   synchronized      every r_g > kCoherent and every dPhi_g varies by < kLocked, ending within
//                     pi/2 of 0 (mod 2 pi)
//   antiphase-groups  every r_g > kCoherent, every dPhi_g varies by < kLocked, some ending
//                     within pi/2 of pi
//   chimera           some r_g > kCoherent and some other r_h < kIncoherent (its metronomes drift
//                     relative to the coherent group)
//   disordered        none of these
// A network of one group is synchronized when r_1 > kCoherent, disordered otherwise.
#pragma once

#include <string>
#include <vector>

#include "sim/analysis/order_parameter.h"

namespace metrosync {

struct NetworkRules {
  // a coherent group: the r > 0.9
  static constexpr double kCoherent = 0.9;
  // an incoherent group: the r < 0.5
  static constexpr double kIncoherent = 0.5;
  // locked groups: their mean phases' difference moves by less than this over the window (rad);
  // wider than the single-platform 0.1 rad because a group's mean phase also carries the spread
  // of its members
  static constexpr double kLocked = 0.5;
};

// Streams (t, per-group order) samples and keeps what the rules need over the window.
class NetworkWindow {
 public:
  // t_end: the run's end; period: a fast period (same time unit)
  NetworkWindow(int groups, double t_end, double period);
  void add(double t, const std::vector<Order>& groups);

  int groups() const { return static_cast<int>(r_sum_.size()); }
  double tStart() const { return t_start_; }  // the window's start (the time unit of t_end)
  long rows() const { return rows_; }
  double meanR(int g) const { return rows_ ? r_sum_[g] / rows_ : 0.0; }
  double dPhiRange(int g) const { return dphi_max_[g] - dphi_min_[g]; }
  double dPhiFinal(int g) const { return dphi_last_[g]; }

 private:
  double t_start_ = 0.0;
  long rows_ = 0;
  std::vector<double> r_sum_, dphi_min_, dphi_max_, dphi_last_;
};

// "synchronized", "chimera", "antiphase-groups" or "disordered" ("unknown": no row in the window).
std::string classifyNetwork(const NetworkWindow& w);

}  // namespace metrosync
