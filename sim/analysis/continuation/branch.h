// What a continuation produces: branches of solutions with their stability, and the special points
// on them (folds, Hopf points, branch points, border crossings).
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "sim/analysis/continuation/system.h"

namespace metrosync::continuation {

struct BranchPoint {
  Vec y;        // (x, p), (n + 1) x 1
  Vec tangent;  // unit, (n + 1) x 1, oriented along the direction of continuation
  Region region;
  CVec eigenvalues;  // of the region's formulas
  double max_real = 0.0;
  bool stable = false;
  // A state on jump border `on_border` (region[on_border] = kOnBorder): the fixed point of
  // weight F_+ + (1 - weight) F_-, F_+ the formulas of the border's positive side.
  int on_border = -1;
  double weight = std::numeric_limits<double>::quiet_NaN();
  // The branch test det [F_x F_p; t^T] as computed with the Jacobian of the tangent (null: not
  // yet): valid while y, tangent and region are those it was computed with.
  struct BranchTestValue {
    Vec y, tangent;
    Region region;
    double value = 0.0;
  };
  std::shared_ptr<const BranchTestValue> branch_test;
  double p() const { return y(y.size() - 1); }
};

// region[k] of a state on jump border k (neither side: both sides' formulas combined).
constexpr int kOnBorder = 2;

enum class BifurcationType { Fold, Hopf, Branch, Border };
const char* toString(BifurcationType t);

struct Bifurcation {
  BifurcationType type = BifurcationType::Fold;
  BranchPoint point;
  std::string detail;                                          // what happens there, in words
  double lyapunov = std::numeric_limits<double>::quiet_NaN();  // Hopf: first Lyapunov coefficient
  int border = -1;                                             // Border: which one
  bool stability_changes = false;
};

// The members of a neutral family at one parameter value (sim/analysis/continuation/family.h):
// traced along its first neutral direction, from one end to the other.
struct FamilyExtent {
  std::vector<Vec> members;  // x of each, in order along the family
  bool closed = false;       // the family closes on itself (no end)
  std::string ends;          // what ends it, in words
};

struct Branch {
  int id = 0;
  // a neutral family (k > 0 zero eigenvalues along it): points are its representative members,
  // extent (one per point) the whole family there
  int neutral = 0;
  std::vector<FamilyExtent> extent;
  std::vector<BranchPoint> points;  // in order along the branch
  std::vector<Bifurcation> special;
  std::string end_backward, end_forward;                         // why each end stopped
  bool max_points_backward = false, max_points_forward = false;  // stopped by the point budget
  // where each end stopped, when its reason names a parameter value (NaN otherwise)
  double end_p_backward = std::numeric_limits<double>::quiet_NaN();
  double end_p_forward = std::numeric_limits<double>::quiet_NaN();
};

struct ContinuationSettings {
  double p_min = 0.0, p_max = 0.0;  // the branch stops where p leaves [p_min, p_max]
  // The unit of p in the arclength (typically the range's span): a step of arclength h moves
  // p by up to h * p_scale or the state by up to h, so that a parameter of any size (a physical
  // friction coefficient of 1e-3) is followed in the same number of steps as a scaled one.
  double p_scale = 1.0;
  double step = 0.02;  // first arclength step
  double step_max = 0.1;
  int max_points = 2000;  // per direction
  int max_branches = 8;   // with branch switching
};

}  // namespace metrosync::continuation
