// The parameter derivatives of sim/analysis/periodic_orbit/physical_model.h against central
// differences of the engine's own equations and jump maps over the rig's fields, every field that
// reaches them (through the constants p: dp/dfield differenced on the rigs), on random states of
// four rigs (Coulomb, static above kinetic with a spring, viscous, fixed), in every mode.
#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "tests/periodic_orbit/fixtures.h"

namespace metrosync::orbit {
namespace {

// Each field moved by -+kStep of its size: the derivatives per relative change, compared in
// units of what the model computes there (rates up to ~400 rad/s^2): truncation O(kStep^2) and
// rounding O(1e-16 / kStep) = 1e-10 of it.
constexpr double kStep = 1e-6;
constexpr double kAgree = 1e-8;

struct Field {
  const char* name;
  double size;  // the field's typical size (where its value is 0: a rig without a spring)
  std::function<double&(Rig&)> at;
};

std::vector<Field> fields() {
  return {
      {"gravity", 10, [](Rig& r) -> double& { return r.gravity_m_s2; }},
      {"platform mass", 0.1, [](Rig& r) -> double& { return r.platform.mass_kg; }},
      {"spring", 10, [](Rig& r) -> double& { return r.platform.spring_N_m; }},
      {"box mass 1", 0.1, [](Rig& r) -> double& { return r.metronomes[0].box_mass_kg; }},
      {"pendulum mass 1", 0.02, [](Rig& r) -> double& { return r.metronomes[0].pendulum_mass_kg; }},
      {"length 2", 0.02, [](Rig& r) -> double& { return r.metronomes[1].length_m; }},
      {"inertia 1", 1e-5, [](Rig& r) -> double& { return r.metronomes[0].inertia_kgm2; }},
      {"damping 2", 0.02, [](Rig& r) -> double& { return r.metronomes[1].damping_kg_s; }},
      {"impulse 1", 1e-5, [](Rig& r) -> double& { return r.metronomes[0].impulse_Nms; }},
      {"impulse 2", 1e-5, [](Rig& r) -> double& { return r.metronomes[1].impulse_Nms; }}};
}

// The law's values as fields too: each one's rig with it moved.
Rig withLawValue(const Rig& rig, int i, double delta) {
  Rig r = rig;
  std::vector<double> v = r.platform.friction.values();
  v[i] += delta;
  r.platform.friction = FrictionLaw(r.platform.friction.kind(), v);
  return r;
}

std::vector<Rig> rigs() {
  const std::string e = "yaml/rigs/experiment.yaml";
  return {testing::shipped(e, {"platform.friction.mu=3e-3"}),
          testing::shipped(e, {"platform.friction={law: coulomb, mu: 2e-3, mu_static: 3e-3}",
                               "platform.spring={k: 30.0}"}),
          testing::shipped(e, {"platform.friction={law: viscous, c: 0.3}"}),
          testing::shipped(e, {"platform.friction={law: fixed}"})};
}

Vec randomState(const PhysicalModel& m, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec y(m.dim());
  y(PhysicalModel::kX) = 0.01 * u(rng);
  y(PhysicalModel::kV) = 0.05 * u(rng);
  for (int j = 0; j < m.n(); ++j) {
    y(m.theta(j)) = u(rng);
    y(m.omega(j)) = 10 * u(rng);
  }
  return y;
}

// The parts one after another, as one vector.
Vec stacked(const std::vector<Vec>& parts) {
  Eigen::Index size = 0;
  for (const Vec& p : parts) size += p.size();
  Vec out(size);
  Eigen::Index at = 0;
  for (const Vec& p : parts) {
    out.segment(at, p.size()) = p;
    at += p.size();
  }
  return out;
}

// What the model computes at y, as one vector, for the rig's model: the rates in each mode, the
// tick of pendulum 0 and of both, the plastic stop, the holding force and the static bound.
Vec everything(const Rig& rig, const Vec& y) {
  const PhysicalModel m(rig);
  std::vector<Vec> parts;
  for (PlatformMode mode :
       {PlatformMode::Stuck, PlatformMode::SlipPositive, PlatformMode::SlipNegative})
    parts.push_back(m.rhs(y, mode));
  parts.push_back(m.tick(y, {0}));
  parts.push_back(m.tick(y, {0, 1}));
  if (m.hasPlatform()) parts.push_back(m.plasticStop(y));
  parts.push_back(Vec::Constant(1, m.holdingForce(y)));
  parts.push_back(Vec::Constant(1, m.coulomb() ? m.equations().dryFriction().staticBound() : 0.0));
  return stacked(parts);
}

// The same derivatives in closed form along the parameter direction dp.
Vec everythingAlong(const PhysicalModel& m, const Vec& y, const Vec& dp) {
  std::vector<Vec> parts;
  for (PlatformMode mode :
       {PlatformMode::Stuck, PlatformMode::SlipPositive, PlatformMode::SlipNegative})
    parts.push_back(m.parameterJacobian(y, mode) * dp);
  parts.push_back(m.tickParameterJacobian(y, {0}) * dp);
  parts.push_back(m.tickParameterJacobian(y, {0, 1}) * dp);
  if (m.hasPlatform()) parts.push_back(m.plasticStopParameterJacobian(y) * dp);
  parts.push_back(Vec::Constant(1, m.holdingForceParameters(y).dot(dp)));
  parts.push_back(Vec::Constant(1, m.coulomb() ? m.staticBoundParameters().dot(dp) : 0.0));
  return stacked(parts);
}

// hi, lo: the rig with a field moved by -+kStep of its size
void expectAgreement(const Rig& rig, const Rig& hi, const Rig& lo, const Vec& y,
                     const std::string& what) {
  const PhysicalModel m(rig);
  ASSERT_TRUE(m.hasParameterDerivatives());
  const Vec dp = (PhysicalModel(hi).parameters() - PhysicalModel(lo).parameters()) / (2 * kStep);
  const Vec fd = (everything(hi, y) - everything(lo, y)) / (2 * kStep);
  const Vec exact = everythingAlong(m, y, dp);
  const double scale = std::max(everything(rig, y).cwiseAbs().maxCoeff(), fd.cwiseAbs().maxCoeff());
  EXPECT_LT((exact - fd).cwiseAbs().maxCoeff(), kAgree * scale)
      << rig.platform.friction.name() << ", " << what;
}

TEST(PhysicalModel, ParameterDerivativesAreTheRigsDifferences) {
  std::mt19937 rng(36);
  for (const Rig& rig : rigs()) {
    const PhysicalModel m(rig);
    for (int trial = 0; trial < 4; ++trial) {
      const Vec y = randomState(m, rng);
      for (const Field& f : fields()) {
        Rig hi = rig, lo = rig;
        const double h = kStep * std::max(std::abs(f.at(hi)), f.size);
        f.at(hi) += h;
        f.at(lo) -= h;
        expectAgreement(rig, hi, lo, y, f.name);
      }
      for (int i = 0; i < static_cast<int>(rig.platform.friction.values().size()); ++i) {
        const double h = kStep * rig.platform.friction.values()[i];
        expectAgreement(rig, withLawValue(rig, i, h), withLawValue(rig, i, -h), y,
                        "law value " + std::to_string(i));
      }
    }
  }
}

// The parameters are the rig's constants: the start state, and a moved theta_c only there.
TEST(PhysicalModel, ParametersHoldTheStartAndTheCriticalAngle) {
  Rig rig = testing::shipped("yaml/rigs/experiment.yaml", {"start.v=0.01"});
  const PhysicalModel m(rig);
  const ParameterLayout& pl = m.parameterLayout();
  EXPECT_EQ(m.startState()(PhysicalModel::kV), 0.01);
  EXPECT_EQ(m.startState()(m.theta(1)), rig.metronomes[1].start_angle_rad);
  rig.metronomes[1].theta_c_rad += 0.01;
  const Vec dp = PhysicalModel(rig).parameters() - m.parameters();
  EXPECT_NEAR(dp(pl.thetaC(1)), 0.01, 1e-15);
  EXPECT_EQ(dp.cwiseAbs().sum() - std::abs(dp(pl.thetaC(1))), 0.0);
}

}  // namespace
}  // namespace metrosync::orbit
