#include "sim/analysis/periodic_orbit/special_points.h"

#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>

#include "base/constants.h"
#include "base/number_text.h"

namespace metrosync::orbit {

namespace {

using Cd = std::complex<double>;

// A located fold whose orbit lies this close (scaled section state) to a symmetric orbit is a
// symmetry-breaking branch point: the asymmetric family passes through the symmetric orbit
// there, located to ~1e-10 in arclength.
constexpr double kSymmetric = 1e-6;
// Orbits this far from symmetric are asymmetric: far above the rounding of a symmetric family's
// state (~1e-13), far below a step's distance from a branch point on the asymmetric side (the
// asymmetry grows as the root of the parameter's distance: ~1e-2 a step away).
constexpr double kAsymmetric = 1e-8;
// A complex pair needs this imaginary part to be a torus, not two real multipliers meeting.
constexpr double kComplex = 1e-9;

// The multiplier (or pair) that the zero of `kind` is about: the one nearest to +1, -1, or the
// pair whose product is nearest to 1.
std::pair<int, int> critical(TestKind kind, const CVec& mu) {
  std::pair<int, int> best{0, 0};
  double dist = std::numeric_limits<double>::infinity();
  for (int i = 0; i < mu.size(); ++i) {
    if (kind == TestKind::Torus) {
      for (int j = i + 1; j < mu.size(); ++j)
        if (std::abs(mu(i) * mu(j) - 1.0) < dist)
          dist = std::abs(mu(i) * mu(j) - 1.0), best = {i, j};
      continue;
    }
    const double target = kind == TestKind::PeriodDoubling ? -1.0 : 1.0;
    if (std::abs(mu(i) - target) < dist) dist = std::abs(mu(i) - target), best = {i, i};
  }
  return best;
}

}  // namespace

const std::vector<TestKind>& testKinds() {
  static const std::vector<TestKind> k = {TestKind::Fold, TestKind::Branch,
                                          TestKind::PeriodDoubling, TestKind::Torus};
  return k;
}

double testFunction(TestKind kind, const FamilyMap& fm, const FamilyPoint& q) {
  const CVec& mu = q.orbit.multipliers;
  switch (kind) {
    case TestKind::Fold:
      return q.tangent(q.tangent.size() - 1);
    case TestKind::Branch:
      // a symmetric family: the antisymmetric modes' multipliers; otherwise the bordered matrix
      return fm.symmetry().kind != SymmetryKind::None ? fm.antisymmetric(q).determinant()
                                                      : fm.bordered(q).determinant();
    case TestKind::PeriodDoubling: {
      Cd prod = 1.0;
      for (int i = 0; i < mu.size(); ++i) prod *= mu(i) + 1.0;
      return prod.real();
    }
    case TestKind::Torus: {
      Cd prod = 1.0;
      for (int i = 0; i < mu.size(); ++i)
        for (int j = i + 1; j < mu.size(); ++j) prod *= mu(i) * mu(j) - 1.0;
      return prod.real();
    }
  }
  return 0.0;
}

double symmetryDistance(const FamilyPoint& q, const ScaledModel& m) {
  return std::min(inPhaseDistance(m, q.orbit.pass.z0), antiPhaseDistance(m, q.orbit.pass.z0));
}

std::optional<OrbitBifurcation> classify(TestKind kind, const FamilyPoint& q, const FamilyPoint& a,
                                         const FamilyPoint& b, const ScaledModel& model,
                                         SymmetryKind symmetry) {
  OrbitBifurcation out;
  out.point = q;
  out.stability_changes = a.stable() != b.stable();
  const CVec& mu = q.orbit.multipliers;
  const auto [i, j] = critical(kind, mu);
  switch (kind) {
    case TestKind::Fold:
      // on asymmetric orbits (a's) that reach a symmetric one: a fold of a symmetric family is
      // a fold
      if (symmetryDistance(q, model) < kSymmetric && symmetryDistance(a, model) > kAsymmetric) {
        out.type = "branch";
        out.meets_symmetric = true;
        out.detail =
            "symmetry-breaking branch point: the asymmetric family meets the symmetric "
            "orbits (multiplier " +
            numberText(mu(i).real(), 9) + ")";
      } else {
        out.type = "fold";
        out.detail = "fold of cycles: the family turns back; a multiplier crosses +1 (" +
                     numberText(mu(i).real(), 9) + ")";
      }
      return out;
    case TestKind::Branch:
      out.type = "branch";
      if (symmetry != SymmetryKind::None)
        out.detail = std::string("symmetry-breaking branch point of the ") + toString(symmetry) +
                     " orbits: a multiplier of the antisymmetric modes crosses +1 (" +
                     numberText(mu(i).real(), 9) + "); asymmetric orbits branch off";
      else
        out.detail = "branch point: another family of orbits crosses; a multiplier crosses +1 (" +
                     numberText(mu(i).real(), 9) + ")";
      return out;
    case TestKind::PeriodDoubling:
      if (std::abs(mu(i).imag()) > kComplex) return std::nullopt;
      out.type = "period-doubling";
      out.detail = "period doubling: a multiplier crosses -1 (" + numberText(mu(i).real(), 9) + ")";
      return out;
    case TestKind::Torus: {
      if (std::abs(mu(i).imag()) <= kComplex || j == i) return std::nullopt;  // neutral saddle
      const double angle = std::abs(std::arg(mu(i)));
      out.type = "torus";
      out.detail = "Neimark-Sacker (torus): multipliers |mu| = " + numberText(std::abs(mu(i)), 9) +
                   " at angles +-" + numberText(angle, 6) +
                   " rad: the amplitudes start to modulate, period " +
                   numberText(2 * kPi / angle, 6) + " orbits";
      return out;
    }
  }
  return std::nullopt;
}

OrbitBifurcation classifyEvents(const FamilyPoint& q, const FamilyPoint& a, const FamilyPoint& b) {
  OrbitBifurcation out;
  out.point = q;
  out.stability_changes = a.stable() != b.stable();
  // said as the parameter increases
  const bool up = b.p >= a.p;
  const EventCounts &lo = (up ? a : b).measures.events, &hi = (up ? b : a).measures.events;
  for (size_t i = 0; i < lo.ticks.size(); ++i) {
    if (lo.ticks[i] == hi.ticks[i]) continue;
    out.type = "grazing";
    out.detail = "metronome " + std::to_string(i + 1) + " " +
                 (hi.ticks[i] < lo.ticks[i] ? "stops" : "starts") +
                 " reaching theta_c as the parameter increases: ticks per period " +
                 std::to_string(lo.ticks[i]) + " -> " + std::to_string(hi.ticks[i]);
    return out;
  }
  out.type = "sliding";
  out.detail =
      "the platform's switches change as the parameter increases (per period): "
      "stick-slip " +
      std::to_string(lo.stick_slip) + " -> " + std::to_string(hi.stick_slip) + ", slip reversals " +
      std::to_string(lo.reversals) + " -> " + std::to_string(hi.reversals) + ", made by ticks " +
      std::to_string(lo.at_ticks) + " -> " + std::to_string(hi.at_ticks);
  return out;
}

}  // namespace metrosync::orbit
