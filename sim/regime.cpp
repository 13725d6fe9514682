#include "sim/regime.h"

#include <algorithm>
#include <stdexcept>

namespace metrosync {

namespace {
constexpr double kPi = 3.141592653589793;
constexpr double kTwoPi = 6.283185307179586;
}  // namespace

const char* toString(Regime r) {
  switch (r) {
    case Regime::Death:
      return "death";
    case Regime::Suppression:
      return "suppression";
    case Regime::Drift:
      return "drift";
    case Regime::InPhase:
      return "in-phase";
    case Regime::Antiphase:
      return "antiphase";
    case Regime::PhaseLocked:
      return "phase-locked";
    case Regime::Unsettled:
      return "unsettled";
    case Regime::Alive:
      return "alive";
    case Regime::None:
      return "none";
    case Regime::Unknown:
      return "unknown";
  }
  return "unknown";
}

double wrapToPi(double angle_rad) {
  // remainder() gives [-pi, pi]; move -pi to +pi so the interval is (-pi, pi]
  double w = std::remainder(angle_rad, kTwoPi);
  if (w <= -kPi) w += kTwoPi;
  return w;
}

RegimeWindow::RegimeWindow(double tau_end, RegimeRules rules)
    : tau_start_((1.0 - rules.window_fraction) * tau_end), rules_(rules) {}

void RegimeWindow::add(const EnvelopeRow& row) {
  last_ = row;
  have_last_ = true;
  if (row.tau < tau_start_) return;
  if (rows_in_window_ == 0) {
    psi_min_ = row.psi;
    psi_max_ = row.psi;
  } else {
    const size_t m = std::min(row.psi.size(), psi_min_.size());
    for (size_t j = 0; j < m; ++j) {
      psi_min_[j] = std::min(psi_min_[j], row.psi[j]);
      psi_max_[j] = std::max(psi_max_[j], row.psi[j]);
    }
  }
  ++rows_in_window_;
}

std::vector<double> RegimeWindow::psiRange() const {
  std::vector<double> range(last_.psi.size(), 0.0);
  if (rows_in_window_ == 0) return range;  // judged on the last row alone
  for (size_t j = 0; j < range.size() && j < psi_min_.size(); ++j)
    range[j] = psi_max_[j] - psi_min_[j];
  return range;
}

RegimeVerdict classifyRegime(const RegimeWindow& window, const std::vector<double>& theta_c,
                             const std::vector<bool>& locked) {
  RegimeVerdict v;
  if (window.empty()) return v;  // Unknown
  const EnvelopeRow& last = window.last();
  const size_t n = last.A.size();
  if (theta_c.size() != n)
    throw std::invalid_argument("classifyRegime: " + std::to_string(theta_c.size()) +
                                " critical angles for " + std::to_string(n) + " metronomes");
  if (!locked.empty() && locked.size() != n)
    throw std::invalid_argument("classifyRegime: locked mask has the wrong size");
  auto isLocked = [&](size_t i) { return !locked.empty() && locked[i]; };

  v.window_rows = window.rowsInWindow();
  v.window_tau_start = window.tauStart();
  v.psi_range = window.psiRange();
  for (double p : last.psi) v.psi_final.push_back(wrapToPi(p));

  // a non-finite state has no regime (only a failed run ends like that)
  for (double a : last.A)
    if (!std::isfinite(a)) return v;
  for (double p : last.psi)
    if (!std::isfinite(p)) return v;

  // death and suppression: final amplitude against the escapement's critical angle
  int swinging = 0, dead = 0;
  v.alive.assign(n, -1);
  for (size_t i = 0; i < n; ++i) {
    if (isLocked(i)) continue;
    ++swinging;
    v.alive[i] = last.A[i] >= theta_c[i] ? 1 : 0;
    dead += v.alive[i] == 0;
  }
  const RegimeRules& r = window.rules();
  if (swinging == 0) {
    v.regime = Regime::None;
    return v;
  }
  if (dead == swinging) {
    v.regime = Regime::Death;
    return v;
  }
  if (dead > 0) {
    v.regime = Regime::Suppression;
    return v;
  }

  // phase rules on psi_j = phi_1 - phi_j, j = 2..N (index j-2), both pendulums swinging
  std::vector<size_t> judged;
  if (!isLocked(0))
    for (size_t j = 1; j < n; ++j)
      if (!isLocked(j) && j - 1 < last.psi.size()) judged.push_back(j - 1);
  if (judged.empty()) {
    v.regime = Regime::Alive;
    return v;
  }
  bool drift = false, settled = true, in_phase = true, antiphase = true;
  for (size_t k : judged) {
    drift = drift || v.psi_range[k] > r.drift_rad;
    settled = settled && v.psi_range[k] < r.settled_rad;
    in_phase = in_phase && std::fabs(wrapToPi(last.psi[k])) <= r.in_phase_rad;
    antiphase = antiphase && std::fabs(wrapToPi(last.psi[k] - kPi)) <= r.antiphase_rad;
  }
  if (drift)
    v.regime = Regime::Drift;
  else if (settled && in_phase)
    v.regime = Regime::InPhase;
  else if (settled && antiphase)
    v.regime = Regime::Antiphase;
  else if (settled)
    v.regime = Regime::PhaseLocked;
  else
    v.regime = Regime::Unsettled;
  return v;
}

RegimeVerdict classifyRegime(const std::vector<EnvelopeRow>& rows, double tau_end,
                             const std::vector<double>& theta_c, const std::vector<bool>& locked,
                             RegimeRules rules) {
  RegimeWindow w(tau_end, rules);
  for (const auto& row : rows) w.add(row);
  return classifyRegime(w, theta_c, locked);
}

}  // namespace metrosync
