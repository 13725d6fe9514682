// Static friction at mu_static == mu is Coulomb's law: on the direct engine the same steps, events
// and bits, for the rigs of every kind of platform motion the engine meets (stick-slip with
// ticks, a slip from rest, creeping on a spring). mu_static above mu changes the run (so the key is
// not ignored) where the push on a stuck board reaches the kinetic bound.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/common/full_model_trial.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

using testing_support::expectSameBits;
using testing_support::runOn;
using testing_support::Trial;

Trial run(const std::string& file, const std::vector<std::string>& sets) {
  return runOn("direct",
               loadRigFile(std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/" + file, sets));
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
