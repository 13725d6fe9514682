// The full model's continuation: the paper's f4.3 family in mu at epsilon = 0.073 (its in-phase
// orbits lose stability at a torus point and fold back), located the same from both sides with
// other steps; each located point with a stable side checked by long direct runs of the engine on
// both sides; every orbit of a family a periodic orbit to 1e-10.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/analysis/periodic_orbit/full_continuation.h"
#include "sim/analysis/periodic_orbit/orbit_continuation.h"
#include "sim/engines/direct/direct_engine.h"
#include "sim/record/run_report.h"
#include "tests/periodic_orbit/fixtures.h"
#include "yaml/rig_loader.h"

namespace metrosync::orbit {
namespace {

const std::string kF43 = "yaml/rigs/paper/f4.3-mu0.2.yaml";
const std::string kMu = "platform.friction.mu";

OrbitProblem problemOf(const std::string& path, const std::string& key,
                       std::vector<std::string> sets = {}) {
  OrbitProblem prob;
  prob.rig_at = [=](double p) {
    auto o = sets;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s=%.17g", key.c_str(), p);
    o.push_back(buf);
    return testing::shipped(path, o);
  };
  return prob;
}

const OrbitBifurcation* find(const Family& f, const std::string& type) {
  for (const OrbitBifurcation& b : f.special)
    if (b.type == type) return &b;
  return nullptr;
}

// The f4.3 family from its settled start at mu = 0.2, first step h (in mu).
Family f43(double h) {
  const OrbitProblem prob = problemOf(kF43, kMu);
  const ReturnMap map(prob.rig_at(0.2), 0);
  FamilySettings s;
  s.p_min = 0.2, s.p_max = 0.3, s.step = h;
  return continueFamily(prob, testing::settledOrbit(map), 0.2, s);
}

TEST(FullContinuation, F43TorusAndFoldIndependentOfStepAndDirection) {
  const Family a = f43(0.002);
  ASSERT_EQ(a.symmetry, SymmetryKind::InPhase);
  const OrbitBifurcation *torus = find(a, "torus"), *fold = find(a, "fold");
  ASSERT_TRUE(torus && fold);
  EXPECT_TRUE(torus->stability_changes);
  // the slow flow's Hopf and fold are 0.28909 and 0.30739; the full model's lie O(epsilon) below
  EXPECT_NEAR(torus->point.p, 0.2786, 5e-3);
  EXPECT_NEAR(fold->point.p, 0.2890, 5e-3);
  for (const FamilyPoint& q : a.points) EXPECT_LE(q.orbit.residual, 1e-10) << "at mu " << q.p;
  // from the lower (unstable) half, with a step 8 times larger: the fold and then the torus are
  // met the other way round
  const FamilyPoint* lower = nullptr;
  for (const FamilyPoint& q : a.points)
    if (q.p < 0.25 && q.measures.A[0] < 1.4) lower = &q;
  ASSERT_TRUE(lower);
  const OrbitProblem prob = problemOf(kF43, kMu);
  FamilySettings s;
  s.p_min = 0.2, s.p_max = 0.3, s.step = 0.016;
  const Family b = continueFamily(prob, lower->orbit, lower->p, s);
  const OrbitBifurcation *torus_b = find(b, "torus"), *fold_b = find(b, "fold");
  ASSERT_TRUE(torus_b && fold_b);
  EXPECT_NEAR(torus_b->point.p, torus->point.p, 1e-7);
  EXPECT_NEAR(fold_b->point.p, fold->point.p, 1e-7);
  std::printf("torus %.10f / %.10f, fold %.10f / %.10f\n", torus->point.p, torus_b->point.p,
              fold->point.p, fold_b->point.p);
}

// The in-phase orbit at mu, perturbed antisymmetrically (the torus's modes: the metronomes swing
// against each other), run by the engine for `periods`: its distance from the orbit's state on
// the section at the end (on the section of the first crossing after the run).
double distanceAfter(double mu, const Orbit& near, double periods) {
  const OrbitProblem prob = problemOf(kF43, kMu);
  const ReturnMap map(prob.rig_at(mu), 0);
  const auto orbit = shoot(map, near.u, near.period);
  EXPECT_TRUE(orbit.has_value());
  Vec z = orbit->pass.z0;
  z(map.model().theta(1)) += 1e-3;
  Rig r = prob.rig_at(mu);
  map.model().setStart(r, z);
  r.sim.t_end_s = map.model().seconds(periods * orbit->period);
  r.sim.sample_s = r.sim.t_end_s;
  FinalStateSink none;
  const RunReport rep = runDirectModel(r, none);
  EXPECT_TRUE(rep.complete);
  const Pass back = map.firstCrossing(map.model().stateFromRow(rep.final_trajectory_row), 20.0);
  return (back.u1 - orbit->u).lpNorm<Eigen::Infinity>();
}

TEST(FullContinuation, TorusConfirmedByDirectRuns) {
  const Family a = f43(0.005);
  const OrbitBifurcation* torus = find(a, "torus");
  ASSERT_TRUE(torus);
  // 1500 periods: below, the perturbation decays by |mu| ~ 0.996 per period (to ~1e-5); above,
  // it grows by ~1.004 per period and the pair leaves the in-phase orbit
  const double below = distanceAfter(torus->point.p - 0.008, torus->point.orbit, 1500);
  const double above = distanceAfter(torus->point.p + 0.006, torus->point.orbit, 1500);
  EXPECT_LT(below, 1e-3) << "the state must persist below the torus point";
  EXPECT_GT(above, 1e-1) << "the state must leave above it";
  std::printf("torus at %.8f: distance after 1500 periods %.3g below, %.3g above\n", torus->point.p,
              below, above);
}

}  // namespace
}  // namespace metrosync::orbit

namespace metrosync::orbit {
namespace {

// Ticks of one metronome (rig index) in a run.
struct TickCounter : RunSink {
  int metronome = 0;
  int ticks = 0;
  bool wantsEventRows() const override { return false; }
  bool wantsEventRecords() const override { return true; }
  void eventRecord(const char* kind, int m, const std::vector<double>&,
                   const std::vector<double>&) override {
    ticks += std::string(kind) == "tick" && m == metronome;
  }
};

// f4.3 at mu = 0.3 and epsilon = 0.02 settles into suppression: metronome 1 swings at A = 0.64,
// below its theta_c = 0.9. Lowering its theta_c, the family ends where it starts reaching it.
TEST(FullContinuation, GrazingConfirmedByDirectRuns) {
  const OrbitProblem prob =
      problemOf("yaml/rigs/paper/f4.3-mu0.3.yaml", "metronomes.0.theta_c", {"epsilon=0.02"});
  const SettledOrbit st = settleOrbit(prob.rig_at(0.9), prob.ret, prob.newton);
  OrbitProblem p = prob;
  p.pendulum = st.pendulum;
  FamilySettings s;
  s.p_min = 0.5, s.p_max = 0.9;
  const Family f = continueFamily(p, st.orbit, 0.9, s);
  const OrbitBifurcation* g = find(f, "grazing");
  ASSERT_TRUE(g) << f.end_backward;
  EXPECT_NEAR(g->point.p, 0.642, 0.01);
  // engine runs of 300 periods from the orbit at the point, its theta_c on either side
  auto ticks = [&](double theta_c) {
    Rig r = prob.rig_at(theta_c);
    const ReturnMap map(r, p.pendulum);
    map.model().setStart(r, g->point.orbit.pass.z0);
    r.sim.t_end_s = map.model().seconds(300 * g->point.orbit.period);
    TickCounter c;
    EXPECT_TRUE(runDirectModel(r, c).complete);
    return c.ticks;
  };
  EXPECT_EQ(ticks(g->point.p + 0.005), 0) << "above the point metronome 1 stays below theta_c";
  EXPECT_GT(ticks(g->point.p - 0.005), 0) << "below it, it ticks: the state leaves";
}

}  // namespace
}  // namespace metrosync::orbit

namespace metrosync::orbit {
namespace {

// f4.1: no friction at all (mu = 0). The platform's momentum is conserved, its velocity on the
// section neutral (a multiplier exactly 1): the family is followed at the start's drift.
TEST(FullContinuation, FrictionlessPlatformFollowedAtItsDrift) {
  const OrbitProblem prob = problemOf("yaml/rigs/paper/f4.1.yaml", "metronomes.0.nu");
  const SettledOrbit st = settleOrbit(prob.rig_at(0.5), prob.ret, prob.newton);
  ASSERT_TRUE(
      neutralVelocity(ReturnMap(prob.rig_at(0.5), st.pendulum).section(), st.orbit.pass.jacobian));
  OrbitProblem p = prob;
  p.pendulum = st.pendulum;
  FamilySettings s;
  s.p_min = 0.45, s.p_max = 0.55;
  const Family f = continueFamily(p, st.orbit, 0.5, s);
  ASSERT_GT(f.points.size(), 10u) << f.end_backward << " / " << f.end_forward;
  EXPECT_NE(f.end_forward.find("reached the end of the range"), std::string::npos);
  for (const FamilyPoint& q : f.points) {
    EXPECT_LE(q.orbit.residual, 1e-10) << "at nu " << q.p;
    EXPECT_EQ(q.orbit.pass.z0(ScaledModel::kV), st.orbit.pass.z0(ScaledModel::kV));
    EXPECT_TRUE(q.orbit.neutral);
  }
}

}  // namespace
}  // namespace metrosync::orbit
