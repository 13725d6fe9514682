// The continuation parameter in units of its range: q = (p - p0) / p_scale, so that the
// arclength weighs one range of p like O(1) of the state (ContinuationSettings::p_scale). A
// ContinuationSystem in p becomes one in q, and the branches found in q come back in p, with the
// range's ends exact (q_max maps to p_max itself, not to p0 + scale * q_max rounded).
#pragma once

#include "sim/analysis/continuation/branch.h"

namespace metrosync::continuation {

class ParameterScale {
 public:
  ParameterScale(double p0, const ContinuationSettings& s);

  double p(double q) const;
  double q(double p) const;
  // The system in q (every callback given p(q)).
  ContinuationSystem system(const ContinuationSystem& sys) const;
  // The settings in q: the range [q(p_min), q(p_max)], p_scale 1; steps unchanged (already in
  // units of the scaled arclength).
  ContinuationSettings settings(const ContinuationSettings& s) const;
  // A branch found in q, back in p (points, tangents, special points).
  void restore(Branch& b) const;
  void restore(BranchPoint& q) const;

 private:
  double p0_, scale_, p_min_, p_max_, q_min_, q_max_;
};

}  // namespace metrosync::continuation
