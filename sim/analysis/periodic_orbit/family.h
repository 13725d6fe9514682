// A family of periodic orbits of the full model along one rig key, and its special points: what
// the full model's continuation (orbit_continuation.h) produces.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sim/analysis/periodic_orbit/orbit_measures.h"
#include "sim/analysis/periodic_orbit/return_map.h"
#include "sim/analysis/periodic_orbit/shooting.h"
#include "sim/analysis/periodic_orbit/symmetry.h"

namespace metrosync::orbit {

// The problem: the rig at each value p of the key (throws for a value the rig refuses), the
// section's pendulum, and the accuracies.
struct OrbitProblem {
  std::function<Rig(double p)> rig_at;
  int pendulum = 0;
  ReturnSettings ret;
  NewtonSettings newton;
};

struct FamilySettings {
  double p_min = 0.0, p_max = 1.0;  // the family stops where p leaves [p_min, p_max]
  double step = 0.0;                // first step in p (0: (p_max - p_min) / 50)
  // The largest arclength step in (u, p / span), span = p_max - p_min: at most this change of
  // the section state (scaled) or of the parameter's share of its range per step.
  double step_max = 0.04;
  int max_points = 400;  // per direction
  bool locate = true;    // locate the special points (otherwise only detect them)
};

// One orbit of the family.
struct FamilyPoint {
  double p = 0.0;
  Orbit orbit;
  Vec tangent;  // ((k + 1) x 1) in (w, p / span), unit, along the direction of continuation
  Vec dFdp;     // (k x 1): B^T d(P(u) - u) / d(p / span)  (family_map.h: u = B w)
  OrbitMeasures measures;
  bool stable() const { return orbit.maxModulus() < 1.0; }
};

// fold (of cycles), torus (Neimark-Sacker), period-doubling, branch (symmetry-breaking),
// grazing (a pendulum stops or starts reaching theta_c), sliding (a stick phase appears or
// vanishes)
struct OrbitBifurcation {
  std::string type;
  FamilyPoint point;
  std::string detail;
  bool stability_changes = false;
  // a branch point reached along asymmetric orbits (their fold on a symmetric orbit): the family
  // beyond it is the mirror image of the one before
  bool meets_symmetric = false;
};

struct Family {
  // the symmetric orbits it stays on (symmetry.h: followed inside their subspace), or none
  SymmetryKind symmetry = SymmetryKind::None;
  std::vector<FamilyPoint> points;  // in order along the family (increasing p at the start)
  std::vector<OrbitBifurcation> special;
  std::string end_backward, end_forward;  // why each end stopped
};

}  // namespace metrosync::orbit
