#include "sim/analysis/periodic_orbit/symmetry.h"

#include <cmath>
#include <limits>
#include <vector>

namespace metrosync::orbit {

const char* toString(SymmetryKind k) {
  switch (k) {
    case SymmetryKind::None:
      return "none";
    case SymmetryKind::InPhase:
      return "in-phase";
    case SymmetryKind::AntiPhase:
      return "antiphase";
  }
  return "none";
}

bool identicalPair(const ScaledModel& m) {
  if (m.n() != 2) return false;
  const ScaledParams& s = m.scaled();
  const int a = m.rigIndex(0), b = m.rigIndex(1);
  return s.nu[a] == s.nu[b] && s.J[a] == s.J[b] && s.theta_c[a] == s.theta_c[b] &&
         s.alpha[a] == s.alpha[b] && s.zeta[a] == s.zeta[b];
}

double inPhaseDistance(const ScaledModel& m, const Vec& z) {
  if (!identicalPair(m)) return std::numeric_limits<double>::infinity();
  return std::max(std::abs(z(m.theta(0)) - z(m.theta(1))), std::abs(z(m.omega(0)) - z(m.omega(1))));
}

double antiPhaseDistance(const ScaledModel& m, const Vec& z) {
  if (!identicalPair(m)) return std::numeric_limits<double>::infinity();
  return std::max({std::abs(z(m.theta(0)) + z(m.theta(1))), std::abs(z(m.omega(0)) + z(m.omega(1))),
                   std::abs(z(ScaledModel::kX)), std::abs(z(ScaledModel::kV))});
}

SymmetryReduction reduction(const ReturnMap& map, SymmetryKind kind) {
  const ScaledModel& m = map.model();
  const Section& sec = map.section();
  const int dim = sec.dim();
  SymmetryReduction r;
  r.kind = kind;
  if (kind == SymmetryKind::None) {
    r.B = Mat::Identity(dim, dim);
    return r;
  }
  // the symmetric directions in z; on the section theta_r = 0, so the angles are fixed at 0
  std::vector<Vec> dirs;
  Vec e = Vec::Zero(m.dim());
  if (kind == SymmetryKind::InPhase) {
    if (m.hasSpring()) dirs.push_back(Vec::Unit(m.dim(), ScaledModel::kX));
    if (m.hasPlatform()) dirs.push_back(Vec::Unit(m.dim(), ScaledModel::kV));
    e(m.omega(0)) = e(m.omega(1)) = 1.0;
  } else {
    e(m.omega(0)) = 1.0, e(m.omega(1)) = -1.0;
  }
  dirs.push_back(e);
  r.B.resize(dim, static_cast<int>(dirs.size()));
  for (size_t k = 0; k < dirs.size(); ++k) r.B.col(k) = sec.coordinatesOf(dirs[k]).normalized();
  const Mat Q = Eigen::HouseholderQR<Mat>(r.B).householderQ();
  r.C = Q.rightCols(dim - r.B.cols());
  return r;
}

}  // namespace metrosync::orbit
