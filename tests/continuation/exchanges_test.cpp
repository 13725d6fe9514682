// `continue --all` on identical metronomes (sim/analysis/continuation/exchanges.h,
// state_traces.h): a locked state that is another with metronomes exchanged gets that state's
// branches mapped through the exchange instead of followed again. The mapped branches must be
// the ones the continuation follows from the copy itself (the slow flow's symmetry, checked
// against a walk that knows nothing of it), and the states found must not depend on the threads.
#include "sim/analysis/continuation/exchanges.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "base/number_text.h"
#include "models/scaling.h"
#include "sim/analysis/continuation/start_states.h"
#include "sim/analysis/continuation/state_traces.h"
#include "yaml/rig_loader.h"

namespace metrosync::continuation {
namespace {

using Cd = std::complex<double>;

// yaml/rigs/n3.yaml (three identical metronomes) in platform.friction.mu from its own 6.5e-4 to
// 0.01, the settings `continue` gives it.
SlowFlowContinuationSpec n3Spec() {
  const std::string path = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/n3.yaml";
  const auto rig =
      std::make_shared<const RigAtValues>(readRigFile(path), path, std::vector<std::string>{},
                                          std::vector<std::string>{"platform.friction.mu"});
  SlowFlowContinuationSpec spec;
  spec.params = [rig](double mu) { return computeScaled(rig->at({mu})); };
  spec.from = 6.5e-4, spec.to = 0.01;
  spec.settings.p_min = spec.from, spec.settings.p_max = spec.to;
  spec.settings.p_scale = spec.to - spec.from;
  spec.settings.step = 0.01, spec.settings.step_max = 0.05 * std::sqrt(1.5);
  spec.settings.max_points = 300;
  return spec;
}

TEST(Exchanges, ExchangeOfFindsThePermutationAndTheRotation) {
  const std::vector<Cd> z = {{1.0, 0.0}, {0.2, 0.7}, {-0.4, 0.1}};
  const Cd turn = std::polar(1.0, 0.8);
  const std::vector<Cd> copy = {z[2] * turn, z[0] * turn, z[1] * turn};  // copy_i = e^{ic} z_s(i)
  const auto sigma = exchangeOf(copy, z, {0, 0, 0}, 1e-9);
  ASSERT_TRUE(sigma);
  EXPECT_EQ(*sigma, (std::vector<int>{2, 0, 1}));
  EXPECT_EQ(exchangedReference(*sigma, 0), 1);  // the copy's metronome 1 carries z_0
  // metronomes 0 and 2 differ: no exchange may move z_2 onto metronome 0
  EXPECT_FALSE(exchangeOf(copy, z, {0, 0, 2}, 1e-9));
  std::vector<Cd> other = copy;
  other[1] *= 1.001;  // not a copy
  EXPECT_FALSE(exchangeOf(other, z, {0, 0, 0}, 1e-9));
}

TEST(Exchanges, StatesFoundDoNotDependOnTheThreads) {
  const SlowFlowContinuationSpec spec = n3Spec();
  const SlowFlowProblem grid(spec.params, spec.from, 0);
  const std::vector<Vec> one = allLockedStates(grid, spec.from, 1);
  const std::vector<Vec> three = allLockedStates(grid, spec.from, 3);
  ASSERT_GT(one.size(), 2u);
  ASSERT_EQ(one.size(), three.size());
  for (size_t k = 0; k < one.size(); ++k) EXPECT_EQ(one[k], three[k]) << k;
}

// Each copy's mapped branches against the branches followed from the copy itself: the same
// number, of the same points (amplitudes and phase differences, rotation-free), stability and
// special points.
TEST(Exchanges, MappedBranchesAreTheCopysOwn) {
  const SlowFlowContinuationSpec spec = n3Spec();
  const SlowFlowProblem grid(spec.params, spec.from, 0);
  const std::vector<Vec> states = allLockedStates(grid, spec.from, 2);
  StateTraces traces(spec, grid, states);
  int copies = 0;
  for (long k = 0; k < static_cast<long>(states.size()); ++k) {
    if (traces.originalOf(k) < 0) continue;
    ++copies;
    const Traced mapped = traces.of(k);
    const std::vector<Cd> z = grid.unpack(states[static_cast<size_t>(k)]);
    const auto prob = problemFor(spec, z);
    const Traced own =
        traceState(prob, prob->pack(z, grid.omega(states[static_cast<size_t>(k)])), spec);
    ASSERT_EQ(mapped.branches.size(), own.branches.size()) << k;
    for (size_t b = 0; b < own.branches.size(); ++b) {
      const Branch &m = mapped.branches[b], &o = own.branches[b];
      ASSERT_EQ(m.points.size(), o.points.size()) << k << " " << b;
      ASSERT_EQ(m.special.size(), o.special.size()) << k << " " << b;
      for (size_t i = 0; i < o.points.size(); ++i) {
        const BranchPoint &q = m.points[i], &r = o.points[i];
        const Vec xq = q.y.head(q.y.size() - 1), xr = r.y.head(r.y.size() - 1);
        EXPECT_NEAR(q.p(), r.p(), 1e-9) << k << " " << b << " " << i;
        EXPECT_EQ(q.stable, r.stable) << k << " " << b << " " << i;
        const auto aq = mapped.prob->amplitudes(xq), ar = own.prob->amplitudes(xr);
        const auto pq = mapped.prob->phaseDifferences(xq), pr = own.prob->phaseDifferences(xr);
        for (size_t j = 0; j < aq.size(); ++j) EXPECT_NEAR(aq[j], ar[j], 1e-7) << k << " " << b;
        for (size_t j = 0; j < pq.size(); ++j)
          EXPECT_NEAR(std::remainder(pq[j] - pr[j], 2 * M_PI), 0.0, 1e-7) << k << " " << b;
      }
      for (size_t e = 0; e < o.special.size(); ++e) {
        EXPECT_EQ(m.special[e].type, o.special[e].type);
        EXPECT_NEAR(m.special[e].point.p(), o.special[e].point.p(), 1e-9);
      }
    }
  }
  EXPECT_GT(copies, 0);  // n3 has states that are copies (else the test proves nothing)
}

}  // namespace
}  // namespace metrosync::continuation
