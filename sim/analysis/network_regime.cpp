#include "sim/analysis/network_regime.h"

#include <algorithm>
#include <cmath>

#include "base/constants.h"

namespace metrosync {

RegimeRules networkPlatformRules() {
  RegimeRules r;
  r.settled_rad = NetworkRules::kLocked;
  r.settle_fraction = 1.0;
  return r;
}

GroupLocking groupLocking(const RegimeWindow& w, const std::vector<int>& alive) {
  std::vector<size_t> idx;
  for (size_t i = 0; i < alive.size(); ++i)
    if (alive[i] == 1) idx.push_back(i);
  GroupLocking g;
  g.alive = static_cast<int>(idx.size());
  g.all_locked = true;
  // each alive metronome with those locked to it (itself included); the largest such set
  std::vector<int> locked_to(idx.size(), 1);
  for (size_t a = 0; a < idx.size(); ++a)
    for (size_t b = a + 1; b < idx.size(); ++b) {
      const bool locked = w.pairRange(idx[a], idx[b]) < NetworkRules::kLocked;
      g.all_locked = g.all_locked && locked;
      locked_to[a] += locked;
      locked_to[b] += locked;
    }
  g.largest_locked = idx.empty() ? 0 : *std::max_element(locked_to.begin(), locked_to.end());
  return g;
}

NetworkWindow::NetworkWindow(int groups, double t_end, double period)
    : r_sum_(groups, 0.0), dphi_min_(groups, 0.0), dphi_max_(groups, 0.0), dphi_last_(groups, 0.0) {
  const RegimeRules rules;
  t_start_ = std::max(
      0.0, std::min((1 - rules.window_fraction) * t_end, t_end - rules.min_periods * period));
}

void NetworkWindow::add(double t, const std::vector<Order>& g) {
  if (t < t_start_) return;
  for (int k = 0; k < groups(); ++k) {
    r_sum_[k] += g[k].r;
    const double d = wrapToPi(g[k].Phi - g[0].Phi);
    // unwrap against the previous row: the difference moves by far less than pi per sample
    const double u = rows_ ? dphi_last_[k] + wrapToPi(d - dphi_last_[k]) : d;
    dphi_min_[k] = rows_ ? std::min(dphi_min_[k], u) : u;
    dphi_max_[k] = rows_ ? std::max(dphi_max_[k], u) : u;
    dphi_last_[k] = u;
  }
  ++rows_;
}

std::string classifyNetwork(const NetworkWindow& w, const std::vector<GroupLocking>& locking) {
  if (w.rows() == 0) return "unknown";
  bool all_coherent = !locking.empty(), all_pairs = true;  // pairs: two or more alive each
  bool all_in_phase = true, locked = true, antiphase = false;
  for (int g = 0; g < w.groups(); ++g) {
    const bool coherent = g < static_cast<int>(locking.size()) && locking[g].coherent();
    all_coherent = all_coherent && coherent;
    all_pairs = all_pairs && coherent && locking[g].alive >= 2;
    all_in_phase = all_in_phase && w.meanR(g) > NetworkRules::kCoherent;
    locked = locked && w.dPhiRange(g) < NetworkRules::kLocked;
    antiphase = antiphase || std::abs(wrapToPi(w.dPhiFinal(g))) > kPi / 2;
  }
  if (all_coherent && all_in_phase && locked)
    return antiphase ? "antiphase-groups" : "synchronized";
  // a chimera: a synchronous part (two or more locked metronomes) beside an incoherent one
  for (const GroupLocking& a : locking)
    for (const GroupLocking& b : locking)
      if (&a != &b && a.coherent() && a.alive >= 2 && b.incoherent()) return "chimera";
  // every group locked within itself (a group of one metronome says nothing of that)
  return all_pairs ? "coherent-groups" : "disordered";
}

PlatformsVerdict classifyPlatforms(const NetworkWindow& w, const std::vector<RegimeWindow>& windows,
                                   const std::vector<std::vector<double>>& theta_c) {
  PlatformsVerdict v;
  std::vector<GroupLocking> locking;
  for (std::size_t p = 0; p < windows.size(); ++p) {
    v.platforms.push_back(theta_c[p].empty() ? RegimeVerdict{}
                                             : classifyRegime(windows[p], theta_c[p]));
    locking.push_back(groupLocking(windows[p], v.platforms.back().alive));
  }
  const bool undecided = std::any_of(v.platforms.begin(), v.platforms.end(),
                                     [](const RegimeVerdict& p) { return p.undecided; });
  if (v.platforms.size() == 1)  // a single rig: SPEC 4's name (unknown when never judged)
    v.label = w.rows() == 0 ? "unknown" : regimeName(v.platforms[0]);
  else if (undecided && w.rows() > 0)  // too short, or dying: a longer run decides
    v.label = toString(Regime::Unsettled);
  else
    v.label = classifyNetwork(w, locking);
  return v;
}

}  // namespace metrosync
