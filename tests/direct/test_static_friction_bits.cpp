// Static friction at mu_static == mu is Coulomb's law: on the direct engine the same steps, events
// and bits, for the rigs of every kind of platform motion the engine meets (stick-slip with
// ticks, a slip from rest, creeping on a spring). mu_static above mu changes the run (so the key is
// not ignored) where the push on a stuck board reaches the kinetic bound.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sim/engines/direct/direct_engine.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

struct Trial {
  RunReport report;
  MemorySink sink;
};

Trial run(const std::string& file, const std::vector<std::string>& sets) {
  Trial r;
  r.report = runDirectModel(
      loadRigFile(std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/" + file, sets), r.sink);
  return r;
}

void expectSameBits(const Trial& a, const Trial& b) {
  ASSERT_TRUE(a.report.complete && b.report.complete);
  EXPECT_EQ(a.report.counts.steps, b.report.counts.steps);
  EXPECT_EQ(a.report.counts.events, b.report.counts.events);
  EXPECT_EQ(a.report.counts.stick_slip, b.report.counts.stick_slip);
  EXPECT_EQ(a.report.counts.slip_reversals, b.report.counts.slip_reversals);
  EXPECT_EQ(a.report.counts.escapements, b.report.counts.escapements);
  EXPECT_EQ(a.sink.trajectory, b.sink.trajectory);  // every row, bit for bit
  ASSERT_EQ(a.sink.events.size(), b.sink.events.size());
  for (std::size_t k = 0; k < a.sink.events.size(); ++k) {
    EXPECT_EQ(a.sink.events[k].first, b.sink.events[k].first);
    EXPECT_EQ(a.sink.events[k].second, b.sink.events[k].second);
  }
}

TEST(StaticFrictionBits, EqualCoefficientsRunAsCoulombsLaw) {
  struct Case {
    const char* file;
    const char* mu;
    bool
        pushed_past_mu;  // the push on the stuck board reaches mu-bar M g (else only ticks move it)
  };
  for (const Case& c : {Case{"bench/experiment-short.yaml", "6.5e-4", true},
                        Case{"hard/creep.yaml", "4.6e-3", true},
                        Case{"experiment-high-friction-antiphase.yaml", "4.6e-3", false}}) {
    SCOPED_TRACE(c.file);
    const std::vector<std::string> shorter = {"simulation.duration=4"};
    const Trial coulomb = run(c.file, shorter);
    const Trial equal =
        run(c.file, {shorter[0], std::string("platform.friction.mu_static=") + c.mu});
    expectSameBits(coulomb, equal);
    EXPECT_GT(coulomb.report.counts.stick_slip, 0) << "the case must exercise stick and slip";
    if (!c.pushed_past_mu) continue;  // only ticks move the board: mu_static never acts
    const Trial above = run(c.file, {shorter[0], std::string("platform.friction.mu_static=1")});
    EXPECT_NE(above.sink.trajectory, coulomb.sink.trajectory) << "mu_static is not ignored";
  }
}

}  // namespace
}  // namespace metrosync
