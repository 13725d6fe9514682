// The shipped rigs: every file in yaml/rigs loads, and the validation's rigs say what the paper
// says (section 4 captions, section 3's measurements), typed in here from the paper.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>

#include "base/constants.h"
#include "fixtures.h"
#include "yaml/network_loader.h"

namespace metrosync {
namespace {

namespace fs = std::filesystem;

// psi0 = phi_1 - phi_2 of a scaled start (theta = A sin phi, thetadot = A cos phi)
double startPsi(const ScaledParams& p) {
  return std::remainder(
      std::atan2(p.theta0[0], p.thetadot0[0]) - std::atan2(p.theta0[1], p.thetadot0[1]), 2 * kPi);
}

double startA(const ScaledParams& p, int i) {
  return std::hypot(p.theta0[i], p.thetadot0[i]);
}

TEST(ShippedRigs, EveryShippedRigLoads) {
  int count = 0;
  for (const auto& e : fs::recursive_directory_iterator(testval::rigsDir())) {
    if (e.path().extension() != ".yaml") continue;
    ++count;
    SCOPED_TRACE(e.path().string());
    if (isNetworkText(readRigFile(e.path().string()))) {  // docs/networks.md
      ASSERT_NO_THROW(loadNetworkFile(e.path().string()));
      continue;
    }
    Rig rig;
    ASSERT_NO_THROW(rig = loadRigFile(e.path().string()));
    ScaledParams p;
    ASSERT_NO_THROW(p = computeScaled(rig));
    EXPECT_GT(p.epsilon, 0.0);
    EXPECT_GT(p.tau_end, 0.0);
  }
  // at least the default rig and the validation's twelve
  EXPECT_GE(count, 13);
}

TEST(ShippedRigs, EveryValidationScenarioHasItsRigUnderItsName) {
  std::set<std::string> names;
  for (const auto& spec : shippedScenarios()) {
    SCOPED_TRACE(spec.file);
    EXPECT_TRUE(names.insert(spec.name).second) << "duplicate scenario " << spec.name;
    const Rig rig = loadRigFile(testval::rigsDir() + "/" + spec.file);
    EXPECT_EQ(rig.name, spec.name);
    EXPECT_EQ(fs::path(spec.file).stem().string(), spec.name);
    EXPECT_GT(spec.regime_tau, 0.0);
  }
  EXPECT_EQ(names.size(), 12u);
}

// The section 4 captions, typed from the paper: nu, mu, J, theta_c, alpha (metronome 2), A(0),
// psi(0); epsilon = 0.073 (the experiment's) by the choice.
struct Caption {
  const char* name;
  double nu, mu, J, theta_c, alpha, A0, psi0;
};

TEST(ShippedRigs, PaperRigsSayWhatTheCaptionsSay) {
  const Caption captions[] = {
      {"f4.1", 0.5, 0.0, 3.6, 0.9, 0.0, 1.9, kPi + 0.05},
      {"f4.2", 0.7, 0.2, 2.8, 0.9, 0.0, 1.9, kPi + 0.4},
      {"f4.3-mu0.2", 0.7, 0.2, 2.8, 0.9, 0.0, 1.9, 0.03},
      {"f4.3-mu0.3", 0.7, 0.3, 2.8, 0.9, 0.0, 1.9, 0.03},
      {"f4.3-mu0.4", 0.7, 0.4, 2.8, 0.9, 0.0, 1.9, 0.03},
      {"f4.4-alpha0.2", 0.7, 0.4, 2.8, 0.9, 0.2, 1.9, kPi + 0.4},
      {"f4.4-alpha2", 0.7, 0.4, 2.8, 0.9, 2.0, 1.9, kPi + 0.4},
      {"f4.4-alpha4", 0.7, 0.4, 2.8, 0.9, 4.0, 1.9, kPi + 0.4},
  };
  for (const Caption& c : captions) {
    SCOPED_TRACE(c.name);
    const ScaledParams p = testval::loadScenario(c.name).scaled;
    // the scaled rig round-trips through its equivalent physical system: rounding only
    const double tol = 1e-12;
    EXPECT_NEAR(p.epsilon, 0.073, tol);
    EXPECT_EQ(p.friction.name(), std::string("coulomb"));
    EXPECT_NEAR(*p.friction.value("mu"), c.mu, tol);
    ASSERT_EQ(p.nu.size(), 2u);
    for (int i = 0; i < 2; ++i) {
      EXPECT_NEAR(p.nu[i], c.nu, tol);
      EXPECT_NEAR(p.J[i], c.J, tol);
      EXPECT_NEAR(p.theta_c[i], c.theta_c, tol);
      EXPECT_NEAR(p.zeta[i], 0.0, tol);
      EXPECT_NEAR(startA(p, i), c.A0, tol);
    }
    EXPECT_NEAR(p.alpha[0], 0.0, tol);
    EXPECT_NEAR(p.alpha[1], c.alpha, 1e-9);  // 1 + eps alpha: relative rounding / eps
    // metronome 2 starts at phase 0, so psi0 is metronome 1's phase
    EXPECT_NEAR(std::atan2(p.theta0[1], p.thetadot0[1]), 0.0, tol);
    EXPECT_NEAR(std::remainder(startPsi(p) - c.psi0, 2 * kPi), 0.0, tol);
    EXPECT_GE(p.tau_end, 300.0);
  }
}

// Section 3: mu-bar = 6.5e-4 (low) and 4.6e-3 (high); epsilon = m/M = 0.073; theta_c = 0.9;
// nu = 0.65; J = 3.14 (the paper's rounded values); starts near in-phase or near antiphase.
TEST(ShippedRigs, ExperimentRigsMatchSectionThree) {
  struct Expect {
    const char* name;
    double mu_bar;
    bool antiphase;
  };
  for (const Expect& e : {Expect{"experiment-low-friction-inphase", 6.5e-4, false},
                          Expect{"experiment-low-friction-antiphase", 6.5e-4, true},
                          Expect{"experiment-high-friction-inphase", 4.6e-3, false},
                          Expect{"experiment-high-friction-antiphase", 4.6e-3, true}}) {
    SCOPED_TRACE(e.name);
    const Rig rig = loadRigFile(testval::rigsDir() + "/" + std::string(e.name) + ".yaml");
    EXPECT_EQ(rig.units, Units::Physical);
    EXPECT_EQ(rig.platform.friction, FrictionLaw::coulomb(e.mu_bar));
    const ScaledParams p = computeScaled(rig);
    // the paper rounds: epsilon 0.073, theta_c 0.9, nu 0.65, J 3.14, mu 0.23 (high friction)
    EXPECT_NEAR(p.epsilon, 0.073, 5e-4);
    EXPECT_NEAR(*p.friction.value("mu"), e.mu_bar / std::pow(p.epsilon, 1.5), 1e-12);
    for (int i = 0; i < 2; ++i) {
      EXPECT_NEAR(p.theta_c[i], 0.9, 5e-3);
      EXPECT_NEAR(p.nu[i], 0.65, 5e-3);
      EXPECT_NEAR(p.J[i], 3.14, 5e-3);
    }
    if (e.mu_bar > 1e-3) {
      EXPECT_NEAR(*p.friction.value("mu"), 0.23, 5e-3);
    }
    // near, not at, the symmetric start (an exact one would stay symmetric forever)
    const double off = std::abs(std::remainder(startPsi(p) - (e.antiphase ? kPi : 0.0), 2 * kPi));
    EXPECT_GT(off, 1e-3);
    EXPECT_LT(off, 0.05);
  }
}

}  // namespace
}  // namespace metrosync
