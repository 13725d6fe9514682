// `metrosync scale`: the JSON object (SPEC section 2) and the text table.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "models/scaling.h"
#include "tools/report/scale_report.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

TEST(ScaleReport, JsonHasExactlyTheSpecKeys) {
  const Rig rig = defaultRig();
  const ScaledParams p = computeScaled(rig);
  const nlohmann::json j = scaleJson(rig, p);
  std::set<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.insert(it.key());
  EXPECT_EQ(keys, (std::set<std::string>{"epsilon", "law", "mu", "nu", "J", "theta_c", "alpha",
                                         "zeta", "A_star", "time_scale"}));
  EXPECT_EQ(j["law"], "coulomb");
  EXPECT_EQ(j["epsilon"].get<double>(), p.epsilon);
  EXPECT_EQ(j["mu"].get<double>(), *p.friction.value("mu"));
  ASSERT_EQ(j["nu"].size(), 2u);
  EXPECT_EQ(j["J"][1].get<double>(), p.J[1]);
  EXPECT_EQ(j["A_star"][0].get<double>(), *p.A_star[0]);
  // time_scale = 1/omega0 = sqrt(I1 / (m1 L1 g)) = sqrt(L / g) for I = m L^2; one rounding
  EXPECT_NEAR(j["time_scale"].get<double>(), std::sqrt(0.0225 / 9.81), 1e-16);
}

TEST(ScaleReport, AStarIsNullBelowTheCriticalImpulseAndViscousGivesC) {
  // metronome 2: J = 1 < J_c = pi * 0.7 * 0.9 = 1.98: it stops, no steady amplitude
  const Rig rig = loadRigText(R"(units: scaled
epsilon: 0.05
platform: {friction: {law: viscous, c: 0.2}}
metronomes:
  - {nu: 0.7, J: 2.8, theta_c: 0.9}
  - {nu: 0.7, J: 1.0, theta_c: 0.9}
simulation: {tau: 10}
)",
                              "r");
  const nlohmann::json j = scaleJson(rig, computeScaled(rig));
  EXPECT_TRUE(j["A_star"][0].is_number());
  EXPECT_TRUE(j["A_star"][1].is_null());
  EXPECT_EQ(j["law"], "viscous");
  EXPECT_FALSE(j.contains("mu"));
  EXPECT_NEAR(j["c"].get<double>(), 0.2, 1e-13);           // scaled c comes back to rounding
  EXPECT_NEAR(j["time_scale"].get<double>(), 1.0, 1e-15);  // equivalent system: omega0 = 1
}

TEST(ScaleReport, TextNamesEveryMetronomeAndParameter) {
  const Rig rig = defaultRig();
  const std::string t = scaleText(rig, computeScaled(rig));
  for (const char* piece : {"experiment", "epsilon", "0.07319", "coulomb", "mu =", "nu", "J_c",
                            "theta_c", "A_star", "\n  A ", "\n  B "})
    EXPECT_NE(t.find(piece), std::string::npos) << piece << " not in\n" << t;
}

}  // namespace
}  // namespace metrosync
