// The limit cycle born at the in-phase state's subcritical Hopf point of the paper's identical
// pair (f4.3 family, mu ~ 0.289): followed by shooting on the reduced polar flow, then checked
// independently: integrating the slow flow itself (complex amplitudes z_i, classical RK4 at a
// small fixed step, not the shooting's polar Verner map) over one period returns to the start;
// the period tends to 2 pi / w at the Hopf point; the trivial Floquet multiplier is 1; the cycle
// of a subcritical Hopf point is unstable and lies on the side where the locked state is stable.
// The Hopf mode is the antisymmetric one: the amplitudes swing against each other, psi about 0.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>

#include "base/constants.h"
#include "sim/analysis/continuation/slow_flow_cycles.h"
#include "tests/continuation/fixtures.h"
#include "yaml/rig_loader.h"

namespace metrosync::continuation {
namespace {

using Cd = std::complex<double>;

ScaledParams f43(double mu) {
  const std::string path = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/paper/f4.3-mu0.2.yaml";
  char a[64];
  std::snprintf(a, sizeof a, "platform.friction.mu=%.17g", mu);
  return computeScaled(loadRigFile(path, {a}));
}

TEST(SlowFlowCycle, InPhaseSubcriticalHopfCycleClosesUnderIndependentIntegration) {
  const SlowFlowProblem prob(f43, 0.28, 0);
  const auto z0 = stateFrom({1.6, 1.6}, {0.0});
  const auto x = solveLocked(prob, prob.pack(z0, prob.omegaGuess(0.28, z0)), 0.28);
  ASSERT_TRUE(x.has_value());
  ContinuationSettings s;
  s.p_min = 0.275, s.p_max = 0.3, s.step = 0.002, s.step_max = 0.005, s.max_branches = 1;
  const Bifurcation* hopf = nullptr;
  const auto branches = continueFrom(prob.system(), *x, 0.28, s);
  for (const Bifurcation& e : branches[0].special)
    if (e.type == BifurcationType::Hopf) hopf = &e;
  ASSERT_NE(hopf, nullptr);
  ASSERT_GT(hopf->lyapunov, 0);  // subcritical
  const ResultCycle c = followSlowFlowCycle(prob, hopf->point, s);
  ASSERT_GT(c.points.size(), 5u) << c.end;
  EXPECT_NEAR(c.points.front().period, kTwoPi / c.frequency, 1e-2);
  for (const ResultCyclePoint& q : c.points) {
    EXPECT_LT(q.value, hopf->point.p());  // the stable side of the locked state
    EXPECT_FALSE(q.stable);
    EXPECT_GT(q.max_multiplier, 1.0);
  }
  // one orbit, integrated independently from the cycle's state: it comes back after one period
  // and not after half of one
  const ResultCyclePoint& q = c.points[c.points.size() / 2];
  const ScaledParams p = f43(q.value);
  const SlowFlowModes modes = prob.modes(hopf->point.region);
  const std::vector<Cd> start = stateFrom(q.A0, q.psi0);
  auto distance = [&](const std::vector<Cd>& z) {
    // the phase symmetry: compare in metronome 1's frame
    const Cd turn = std::polar(1.0, std::arg(start[0]) - std::arg(z[0]));
    return std::max(std::abs(z[0] * turn - start[0]), std::abs(z[1] * turn - start[1]));
  };
  EXPECT_LT(distance(testing::rk4SlowFlow(p, modes, start, q.period, 20000)), 1e-6);
  EXPECT_GT(distance(testing::rk4SlowFlow(p, modes, start, q.period / 2, 10000)), 1e-2);
}

}  // namespace
}  // namespace metrosync::continuation
