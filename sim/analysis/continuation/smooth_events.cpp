#include "sim/analysis/continuation/smooth_events.h"

#include <algorithm>
#include <cmath>

#include "base/number_text.h"
#include "sim/analysis/continuation/arclength.h"
#include "sim/analysis/continuation/newton.h"
#include "sim/analysis/continuation/test_functions.h"

namespace metrosync::continuation {

namespace {

// At a located Hopf point the critical pair has |Re| ~ the location accuracy (1e-10); a pair
// farther than this from the axis means the bialternate product vanished for another reason
// (a neutral saddle, lambda_i = -lambda_j real), which is not a bifurcation.
constexpr double kHopfRealTolerance = 1e-6;
// Below this imaginary part a pair is real (a fold or branch point, not a Hopf point).
constexpr double kHopfImagMin = 1e-8;

struct Located {
  double h;
  Bifurcation b;
};

// The critical pair at a Hopf candidate: index of the eigenvalue with Im > 0 nearest the axis.
int criticalPair(const CVec& ev) {
  int best = -1;
  for (int i = 0; i < ev.size(); ++i)
    if (ev(i).imag() > kHopfImagMin &&
        (best < 0 || std::abs(ev(i).real()) < std::abs(ev(best).real())))
      best = i;
  return best;
}

std::optional<Bifurcation> classifyHopf(const ContinuationSystem& sys, const BranchPoint& q) {
  const int i = criticalPair(q.eigenvalues);
  if (i < 0 || std::abs(q.eigenvalues(i).real()) > kHopfRealTolerance) return std::nullopt;
  Bifurcation b;
  b.type = BifurcationType::Hopf;
  b.point = q;
  b.stability_changes = true;
  if (sys.lyapunov) b.lyapunov = sys.lyapunov(q.y.head(sys.n), q.p(), q.region);
  b.detail = "eigenvalues +-i " + numberText(q.eigenvalues(i).imag()) +
             " cross the imaginary axis; first Lyapunov coefficient " + numberText(b.lyapunov, 4) +
             " (" +
             (std::isnan(b.lyapunov) ? "criticality unknown"
              : b.lyapunov < 0       ? "supercritical: a stable cycle is born"
                                     : "subcritical: an unstable cycle is born") +
             ")";
  return b;
}

Vec switchDirection(const ContinuationSystem& sys, const BranchPoint& q) {
  const Mat M = extendedJacobian(sys, q.y, q.region);
  Eigen::JacobiSVD<Mat> svd(M, Eigen::ComputeFullV);
  const Mat& V = svd.matrixV();
  Vec best = Vec::Zero(sys.n + 1);
  for (int c = sys.n - 1; c <= sys.n; ++c) {
    const Vec v = V.col(c) - V.col(c).dot(q.tangent) * q.tangent;
    if (v.norm() > best.norm()) best = v;
  }
  return best.normalized();
}

}  // namespace

void smoothEvents(const ContinuationSystem& sys, const BranchPoint& a, const BranchPoint& b,
                  double h, std::vector<Bifurcation>& special,
                  std::vector<BranchSwitch>& switches) {
  std::vector<Located> found;
  auto look = [&](const std::function<double(const BranchPoint&)>& g, BifurcationType type) {
    const double ga = g(a), gb = g(b);
    if ((ga > 0) == (gb > 0) || ga == 0.0) return;
    double hf = h;
    const auto q = locateOnStep(sys, a, h, ga, gb, g, &hf);
    if (!q) return;
    std::optional<Bifurcation> bif;
    if (type == BifurcationType::Hopf) {
      bif = classifyHopf(sys, *q);
    } else {
      bif = Bifurcation();
      bif->type = type;
      bif->point = *q;
      bif->stability_changes = true;
      bif->detail = type == BifurcationType::Fold
                        ? "limit point: the branch turns back in the parameter; a real eigenvalue "
                          "crosses 0"
                        : "branch point: another branch of fixed points crosses this one";
    }
    if (bif) found.push_back({hf, *bif});
  };
  look(foldTest, BifurcationType::Fold);
  if (sys.branch_points)
    look([&sys](const BranchPoint& q) { return branchTest(sys, q); }, BifurcationType::Branch);
  look([](const BranchPoint& q) { return hopfTest(q.eigenvalues); }, BifurcationType::Hopf);
  std::sort(found.begin(), found.end(),
            [](const Located& l, const Located& r) { return l.h < r.h; });
  for (const Located& l : found) {
    special.push_back(l.b);
    if (l.b.type == BifurcationType::Branch)
      switches.push_back({l.b.point, switchDirection(sys, l.b.point)});
  }
}

std::optional<BranchPoint> switchBranch(const ContinuationSystem& sys, const BranchSwitch& sw,
                                        double h) {
  // the new branch must be there along the direction; it is followed from the branch point
  // itself both ways (a start beside it would step back onto the old branch)
  if (!correct(sys, sw.at.y, sw.direction, h, sw.at.region)) return std::nullopt;
  return makePoint(sys, sw.at.y, sw.direction, sw.at.region);
}

}  // namespace metrosync::continuation
