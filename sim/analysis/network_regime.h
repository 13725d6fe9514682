// The label of a network's state (docs/networks.md, docs/regimes.md "Networks"), judged over the
// single-platform classifier's window: the last tenth of the run (RegimeRules::window_fraction),
// at least RegimeRules::min_periods fast periods.
//
// Locking. Two phases are locked over the window when their unwrapped difference varies by less
// than NetworkRules::kLocked (max - min over the window), whatever the difference is: a pair in
// antiphase is as locked as a pair in phase. Within a platform (a group), among its alive
// metronomes (RegimeVerdict::alive: A_i above theta_c,i somewhere in the window), a group is
//   coherent    at least one alive metronome, and every pair of its alive metronomes locked;
//   incoherent  at least two alive metronomes, and none of them is locked to more than
//               NetworkRules::kIncoherentShare of them, itself included (its metronomes drift
//               against each other, with no locked majority).
// A group can be neither (most locked, a few drifting; or every pair near the tolerance).
//
// With r_g the mean of group g's Kuramoto r over the window and dPhi_g the unwrapped
// Phi_g - Phi_1 (group 1 the reference), rules in order:
//   synchronized      every group coherent with r_g > kCoherent, every dPhi_g locked (varies by
//                     < kLocked) and ending within pi/2 of 0 (mod 2 pi)
//   antiphase-groups  as synchronized, but some dPhi_g ends more than pi/2 from 0
//   chimera           some group coherent with at least two alive metronomes, and some other
//                     group incoherent
//   coherent-groups   every group coherent with at least two alive metronomes, not as above (one
//                     board in phase and one in antiphase; coherent boards drifting apart)
//   disordered        none of these
//   unsettled         (first of all) some platform's verdict is undecided: the run is shorter
//                     than 5 fast periods, or a metronome is dying in the window
// A network of one group is a single rig: classifyPlatforms names it by its platform's verdict.
//
// A platform's own verdict in a network is judged on the same samples with the same tolerance as
// its group's locking (networkPlatformRules): phases sampled within the period wobble (above), so
// the single rig's 0.1 rad, made for period-averaged envelopes, would call a locked platform
// `unsettled` beside a network label that calls it coherent.
#pragma once

#include <string>
#include <vector>

#include "sim/analysis/order_parameter.h"
#include "sim/analysis/regime.h"

namespace metrosync {

struct NetworkRules {
  // a synchronized group: its r stays above this on average (the r > 0.9)
  static constexpr double kCoherent = 0.9;
  // locked: a phase difference varies by less than this over the window (rad). A locked pair's
  // difference still wobbles within each period (phases from theta = A sin phi with the
  // pendulum's own small-angle frequency, ticks, the board's motion): 0.151 rad for the
  // near-antiphase pair of two-boards-rollers.yaml, 0.049-0.066 rad for pairs locked at scattered
  // phases (chimera-swings.yaml at k = 0; docs/regimes.md). A pair that slips by a twelfth of a
  // cycle over the window is not locked. The same bound holds the groups' mean phases together.
  static constexpr double kLocked = 0.5;
  // incoherent: no alive metronome is locked to more than this share of its group's alive
  // metronomes, itself included (no locked majority: a few solitary drifters beside a locked
  // majority do not make a group incoherent)
  static constexpr double kIncoherentShare = 0.5;
};

// The rules of a platform's own verdict in a network (NetworkVerdict's windows): settled means
// varying by less than NetworkRules::kLocked over the whole window (settle_fraction 1), so that
// a platform is settled exactly when its group's alive metronomes are all locked.
RegimeRules networkPlatformRules();

// How one group's alive metronomes hold together over the window.
struct GroupLocking {
  int alive = 0;            // alive swinging metronomes
  int largest_locked = 0;   // the most alive metronomes locked to one of them (itself included)
  bool all_locked = false;  // every pair of alive metronomes locked (true for one alive)
  bool coherent() const { return alive >= 1 && all_locked; }
  bool incoherent() const {
    return alive >= 2 && largest_locked <= NetworkRules::kIncoherentShare * alive;
  }
};

// The locking of one group from its own regime window (phases relative to its first metronome)
// and its verdict's `alive` (1 alive, 0 dead, -1 locked in its box).
GroupLocking groupLocking(const RegimeWindow& window, const std::vector<int>& alive);

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

// "synchronized", "antiphase-groups", "chimera", "coherent-groups" or "disordered" ("unknown":
// no row in the window). locking: one per group, in the window's group order. (The run's
// `unsettled` is classifyPlatforms', from the platforms' verdicts.)
std::string classifyNetwork(const NetworkWindow& w, const std::vector<GroupLocking>& locking);

// The regime of a run of platforms: each platform's verdict (classifyRegime on its own swinging
// metronomes, scaled theta_c in `theta_c`; a platform without any: Regime::Unknown) and the label.
// The single-platform rules are the one-platform case: a single rig, or a network of one
// platform, is labelled by its platform's verdict (regimeName: in-phase, death, clusters:2+1,
// ...; SPEC 4, docs/regimes.md); two or more platforms by classifyNetwork ("unknown" when the
// window has no row).
struct PlatformsVerdict {
  std::vector<RegimeVerdict> platforms;  // file order
  std::string label;
};
PlatformsVerdict classifyPlatforms(const NetworkWindow& w, const std::vector<RegimeWindow>& windows,
                                   const std::vector<std::vector<double>>& theta_c);

}  // namespace metrosync
