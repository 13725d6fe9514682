// Part 6 of the validation: the slow flow's bifurcations for the paper's families. The located
// points are checked against what is known independently: the f4.4 fold where the paper's
// "suppression before death" begins (3.9 < alpha < 3.95, issue 12) and the in-phase state's Hopf
// point of f4.3 between the paper's mu = 0.2 (in-phase) and 0.3 (not); every point's slow-flow
// side checks pass (the state persists on exactly one side); the report carries the section.
#include <gtest/gtest.h>

#include <sstream>

#include "sim/analysis/validation/validation_bifurcations.h"
#include "sim/engines/engine.h"
#include "tests/validation/fixtures.h"
#include "tools/report/validation_bifurcations_report.h"

namespace metrosync {
namespace {

TEST(ValidationBifurcations, PaperFamiliesLocatedAndCheckedOnBothSides) {
  std::vector<BifurcationFamilySpec> families = paperBifurcationFamilies(true);
  for (auto& f : families) f.full_points = 3;  // the brackets' grids: short, still both sides
  // the brackets on the direct engine (the engines agree, tests/direct; Simbody is 10x slower)
  ValidationEngines direct = testval::engines();
  direct.full_model = [](const Rig& rig, RunSink& sink) {
    return findEngine("direct")->run(rig, sink);
  };
  const auto res = runBifurcationFamilies(families, testval::loadScenarios(), direct, 2);
  ASSERT_EQ(res.size(), 2u);
  const BifurcationFamilyResult &mu = res[0], &alpha = res[1];
  ASSERT_FALSE(mu.points.empty()) << mu.start;
  ASSERT_FALSE(alpha.points.empty()) << alpha.start;
  bool hopf = false, fold = false;
  for (const LocatedPoint& p : mu.points) {
    EXPECT_TRUE(p.pass) << p.type << " at " << p.value;
    if (p.type == "hopf" && p.value > 0.2 && p.value < 0.3) hopf = true;
  }
  for (const LocatedPoint& p : alpha.points) {
    EXPECT_TRUE(p.pass) << p.type << " at " << p.value;
    if (p.type == "fold" && p.value > 3.9 && p.value < 3.95) {
      fold = true;
      EXPECT_TRUE(p.below.persists);  // the suppressed state exists below the fold
      EXPECT_FALSE(p.above.persists);
    }
  }
  EXPECT_TRUE(hopf);
  EXPECT_TRUE(fold);
  // the full model ran at every bracket value
  for (const auto& f : res)
    for (const auto& per_point : f.full)
      for (const FullBracket& b : per_point)
        for (const std::string& regime : b.regimes) EXPECT_FALSE(regime.empty());
  std::ostringstream md;
  mdBifurcations(md, res);
  EXPECT_NE(md.str().find("## 6. Bifurcations of the slow flow"), std::string::npos);
  const nlohmann::json j = validationBifurcationsJson(res);
  EXPECT_EQ(j.size(), 2u);
  EXPECT_EQ(j[1]["param"], "metronomes.1.alpha");
}

}  // namespace
}  // namespace metrosync
