#include "sim/analysis/validation/validation_measures.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <stdexcept>

#include "sim/analysis/compare.h"

namespace metrosync {

double envelopeDistance(const EnvelopeRow& a, const EnvelopeRow& b) {
  if (a.A.size() != b.A.size() || a.A.empty()) return std::numeric_limits<double>::quiet_NaN();
  double d = std::abs(a.A[0] - b.A[0]);
  for (size_t j = 1; j < a.A.size(); ++j)
    d = std::max(d,
                 std::abs(std::polar(a.A[j], -a.psi[j - 1]) - std::polar(b.A[j], -b.psi[j - 1])));
  return d;
}

EnvelopeError envelopeError(const std::vector<EnvelopeRow>& full,
                            const std::vector<EnvelopeRow>& slow, double epsilon, double tau_max) {
  EnvelopeError e;
  std::map<long, const EnvelopeRow*> by_index;
  for (const auto& r : slow) by_index[envelopeIndex(epsilon, r.tau)] = &r;
  for (const auto& f : full) {
    if (f.tau > tau_max) continue;
    const auto it = by_index.find(envelopeIndex(epsilon, f.tau));
    if (it == by_index.end()) continue;
    const EnvelopeRow& s = *it->second;
    const double d = envelopeDistance(f, s);
    if (d > e.max_distance) {
      e.max_distance = d;
      e.tau_at_max = f.tau;
    }
    for (size_t i = 0; i < f.A.size() && i < s.A.size(); ++i)
      e.max_dA = std::max(e.max_dA, std::abs(f.A[i] - s.A[i]));
    for (size_t j = 0; j < f.psi.size() && j < s.psi.size(); ++j)
      e.max_dpsi = std::max(e.max_dpsi, std::abs(wrapToPi(f.psi[j] - s.psi[j])));
    ++e.rows;
  }
  return e;
}

double fitOrder(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size() || x.size() < 2)
    throw std::invalid_argument("fitOrder: need at least two (x, y) pairs");
  double mx = 0, my = 0;
  const double n = static_cast<double>(x.size());
  for (size_t k = 0; k < x.size(); ++k) {
    if (!(x[k] > 0 && y[k] > 0)) throw std::invalid_argument("fitOrder: x and y must be > 0");
    mx += std::log(x[k]) / n;
    my += std::log(y[k]) / n;
  }
  double sxy = 0, sxx = 0;
  for (size_t k = 0; k < x.size(); ++k) {
    const double dx = std::log(x[k]) - mx;
    sxy += dx * (std::log(y[k]) - my);
    sxx += dx * dx;
  }
  if (!(sxx > 0)) throw std::invalid_argument("fitOrder: x values must not all be equal");
  return sxy / sxx;
}

bool finalStatesAgree(const ModelRun& full, const ModelRun& slow, double distance) {
  const Regime a = full.verdict.regime, b = slow.verdict.regime;
  if (a == Regime::Unknown || b == Regime::Unknown || a != b) return false;
  switch (a) {
    case Regime::InPhase:
    case Regime::Antiphase:
    case Regime::PhaseLocked:
    case Regime::Suppression:
      return distance <= kAgreeDistance;
    default:
      return true;  // death (no state left), drift and unsettled (no state to compare)
  }
}

EnvelopeRow exchangedPair(const EnvelopeRow& row) {
  if (row.A.size() != 2 || row.psi.size() != 1) return row;
  return {row.tau, {row.A[1], row.A[0]}, {-row.psi[0]}};
}

bool identicalPair(const ScaledParams& p) {
  if (p.nu.size() != 2) return false;
  auto same = [](const std::vector<double>& v) { return v.size() == 2 && v[0] == v[1]; };
  return same(p.nu) && same(p.J) && same(p.theta_c) && same(p.alpha) && same(p.zeta) &&
         (p.locked.empty() || p.locked[0] == p.locked[1]);
}

}  // namespace metrosync
