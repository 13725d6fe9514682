// The diagrams as users of AUTO and MatCont read them: branches.png gives each branch its own
// colour and each metronome its own marker, labels the special points (LP, H(sub) / H(sup), BP,
// B), draws a family's extent; the boundary curves on sweep maps use colours no regime has.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tools/report/continuation_diagram.h"
#include "tools/report/sweep_maps.h"

namespace metrosync {
namespace {

using namespace continuation;

ResultPoint point(int branch, double p, double a1, double a2, bool stable) {
  ResultPoint q;
  q.branch = branch, q.value = p, q.A = {a1, a2}, q.psi = {0.1}, q.stable = stable;
  return q;
}

ContinuationResult threeBranches() {
  ContinuationResult r;
  r.param = "platform.friction.mu";
  r.metronomes = 2;
  for (int b = 0; b < 3; ++b) {
    r.branches.push_back({b, 3, "", ""});
    for (int k = 0; k < 3; ++k) r.points.push_back(point(b, 0.1 * k, 1.0 + b, 1.0 + b, k < 2));
  }
  const char* types[] = {"fold", "hopf", "branch", "border"};
  for (int k = 0; k < 4; ++k) {
    ResultSpecial s;
    s.at = point(k % 3, 0.1, 1.0, 1.0, true);
    s.type = types[k];
    s.lyapunov = k == 1 ? 0.5 : std::nan("");
    r.special.push_back(s);
  }
  return r;
}

TEST(Diagram, AColourPerBranchAMarkerPerMetronomeLabelledPoints) {
  const ContinuationResult r = threeBranches();
  const std::string script = continuationDiagramScript(r, "d.dat", "b.png");
  for (int b = 0; b < 3; ++b)
    EXPECT_NE(script.find(std::string("lc rgb '") + kBranchColours[b] + "'"), std::string::npos)
        << b;
  EXPECT_EQ(script.find(std::string("lc rgb '") + kBranchColours[3] + "'"), std::string::npos);
  // A_1 and A_2 coincide on every branch: different markers, the first line wider
  EXPECT_NE(script.find("pt 6"), std::string::npos);
  EXPECT_NE(script.find("pt 8"), std::string::npos);
  EXPECT_NE(script.find("with labels"), std::string::npos);
  const std::string data = continuationDiagramData(r);
  for (const char* label : {" LP ", " H(sub) ", " BP ", " B "})
    EXPECT_NE(data.find(label), std::string::npos) << label;
}

// A branch that loses stability at a Hopf point between two of its points: the solid and the
// dashed line meet at the Hopf point (its row once stable, once unstable), not at the next point.
TEST(Diagram, StabilityChangesAtTheLocatedPoint) {
  ContinuationResult r;
  r.param = "platform.friction.mu";
  r.metronomes = 2;
  r.branches.push_back({0, 3, "", ""});
  r.points = {point(0, 0.1, 1.0, 1.0, true), point(0, 0.2, 2.0, 2.0, false),
              point(0, 0.3, 3.0, 3.0, false)};
  ResultSpecial h;
  h.at = point(0, 0.15, 1.5, 1.5, false);
  h.type = "hopf";
  h.lyapunov = 0.5;
  r.special.push_back(h);
  // A_1's curve (its datablock: KEY, A_1, A_1 where stable, A_1 where unstable)
  const std::string data = continuationDiagramData(r);
  const size_t from = data.find("$b0c2 << EOD\n"), to = data.find("EOD\n", from + 12);
  ASSERT_NE(from, std::string::npos) << data;
  const std::string a1 = data.substr(from, to - from);
  EXPECT_NE(a1.find("0.15 1.5 1.5 nan\n"), std::string::npos) << a1;
  EXPECT_NE(a1.find("0.15 1.5 nan 1.5\n"), std::string::npos) << a1;
  EXPECT_EQ(a1.find("0.2 2 2 nan\n"), std::string::npos) << a1;  // no solid line to 0.2
  EXPECT_NE(a1.find("0.2 2 nan 2\n"), std::string::npos) << a1;
}

TEST(Diagram, BoundaryCurvesInColoursNoRegimeUses) {
  const std::vector<std::string> regimes = regimeColours();
  ASSERT_GT(regimes.size(), 10u);
  for (const char* c : {kFoldCurveColour, kHopfCurveColour})
    EXPECT_EQ(std::count(regimes.begin(), regimes.end(), std::string(c)), 0) << c;
  EXPECT_NE(std::string(kFoldCurveColour), kHopfCurveColour);
}

}  // namespace
}  // namespace metrosync
