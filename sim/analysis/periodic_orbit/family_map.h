// The return map of a family, F(u, p) = P(u; p) - u, as the continuation sees it: unknowns
// y = (w, p / span), u = B w (B the symmetric subspace of a symmetric family, symmetry.h, else
// the identity; span the parameter's range, so that a step weighs the section state and the
// parameter's share of its range alike), dF/du from the variational equations and saltation
// matrices, dF/dp by central differences of P in p (any rig key: the key changes the rig, the
// engine runs it), and the pseudo-arclength corrector (Keller) on B^T F = 0 and one linear
// condition c . y = value (the arclength of a step, or p at the end of the range).
#pragma once

#include <memory>
#include <optional>

#include "sim/analysis/periodic_orbit/family.h"
#include "sim/analysis/periodic_orbit/symmetry.h"

namespace metrosync::orbit {

class FamilyMap {
 public:
  FamilyMap(const OrbitProblem& problem, double span);

  // The symmetry the family keeps (set once, before the first point; None by default).
  void setSymmetry(SymmetryKind kind);
  const SymmetryReduction& symmetry() const { return red_; }
  // The platform's velocity is neutral on the whole family (no friction on a free platform):
  // it is held at `velocity` (u = offset + B w), its coordinate and its equation (redundant by
  // the conservation of momentum) left out of the reduction B. After setSymmetry.
  void pinVelocity(double velocity);
  bool pinned() const { return pinned_; }
  // the section state of reduced coordinates w
  Vec uAt(const Vec& w) const { return uOf(w); }
  int dim() const { return dim_; }
  double span() const { return span_; }
  const OrbitProblem& problem() const { return prob_; }

  // The return map at p (the rig rebuilt when p changes). Throws what rig_at throws.
  const ReturnMap& mapAt(double p);
  // y = (w, p / span) of a point
  Vec yOf(const FamilyPoint& q) const;

  // Newton on B^T F(B w, p) = 0 and c . y = value from y0, the column at `dFdp` (reduced)
  // (a chord: it is recomputed at the solution). nullopt when it fails (no convergence, the
  // engine fails, the orbit is lost, the rig refuses p).
  std::optional<FamilyPoint> correct(const Vec& y0, const Vec& c, double value, const Vec& dFdp,
                                     double period_guess, int* iterations = nullptr);
  // Fills in dF/dp (reduced), the unit tangent (the kernel of [B^T dF/du B, B^T dF/dp],
  // oriented along `ref`) and, when `measures`, the orbit's averages and events. Throws
  // OrbitFailure.
  void complete(FamilyPoint& q, const Vec& ref, bool measures);
  // B^T dF/d(p / span) at q's orbit (central differences in p). Throws OrbitFailure.
  Vec parameterDerivative(const FamilyPoint& q) { return dFdp(q.orbit.u, q.p, q.orbit.period); }
  // The bordered matrix [[B^T dF/du B, dF/dp], [tangent^T]] of a completed point.
  Mat bordered(const FamilyPoint& q) const;
  // C^T (dP/du - I) C on the antisymmetric complement (empty without a symmetry).
  Mat antisymmetric(const FamilyPoint& q) const;

 private:
  Vec dFdp(const Vec& u, double p, double period);

  OrbitProblem prob_;
  double span_;
  int dim_ = 0;
  SymmetryReduction red_;
  bool pinned_ = false;
  Vec offset_;  // u = offset_ + B w (the pinned velocity; empty: 0)
  Vec uOf(const Vec& w) const {
    return offset_.size() ? Vec(offset_ + red_.B * w) : Vec(red_.B * w);
  }
  Vec wOf(const Vec& u) const {
    return offset_.size() ? Vec(red_.B.transpose() * (u - offset_)) : Vec(red_.B.transpose() * u);
  }
  double map_p_ = 0.0;
  std::unique_ptr<ReturnMap> map_;
};

}  // namespace metrosync::orbit
