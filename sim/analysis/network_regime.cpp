#include "sim/analysis/network_regime.h"

#include <algorithm>
#include <cmath>

#include "sim/analysis/regime.h"

namespace metrosync {

namespace {
constexpr double kPi = 3.14159265358979323846;
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

std::string classifyNetwork(const NetworkWindow& w) {
  if (w.rows() == 0) return "unknown";
  bool all_coherent = true, any_coherent = false, any_incoherent = false;
  bool locked = true, antiphase = false;
  for (int g = 0; g < w.groups(); ++g) {
    const double r = w.meanR(g);
    all_coherent = all_coherent && r > NetworkRules::kCoherent;
    any_coherent = any_coherent || r > NetworkRules::kCoherent;
    any_incoherent = any_incoherent || r < NetworkRules::kIncoherent;
    locked = locked && w.dPhiRange(g) < NetworkRules::kLocked;
    antiphase = antiphase || std::abs(wrapToPi(w.dPhiFinal(g))) > kPi / 2;
  }
  if (all_coherent && locked) return antiphase ? "antiphase-groups" : "synchronized";
  if (any_coherent && any_incoherent) return "chimera";
  return "disordered";
}

}  // namespace metrosync
