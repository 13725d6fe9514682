// What a continuation produces: branches of solutions with their stability, and the special points
// on them (folds, Hopf points, branch points, border crossings).
#pragma once

#include <limits>
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
  double p() const { return y(y.size() - 1); }
};

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

struct Branch {
  int id = 0;
  std::vector<BranchPoint> points;  // in order along the branch
  std::vector<Bifurcation> special;
  std::string end_backward, end_forward;  // why each end stopped
};

struct ContinuationSettings {
  double p_min = 0.0, p_max = 0.0;  // the branch stops where p leaves [p_min, p_max]
  double step = 0.02;               // first arclength step
  double step_max = 0.1;
  int max_points = 2000;  // per direction
  int max_branches = 8;   // with branch switching
};

}  // namespace metrosync::continuation
