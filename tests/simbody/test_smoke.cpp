#include <gtest/gtest.h>

#include <cstdio>

#include "rigs.h"
#include "sim/engines/simbody/simbody_engine.h"

namespace metrosync {
namespace {

TEST(FullModelSmoke, ExperimentRunsAndLedgerCloses) {
  Rig rig = testrigs::experiment(6.5e-4, 20.0);
  MemorySink sink;
  RunReport r = runSimbody(networkOfOne(rig), sink);
  ASSERT_TRUE(r.complete) << r.failure;
  std::printf("steps %ld evals %ld events %ld ticks %ld %ld stickslip %ld wall %.3f\n",
              r.counts.steps, r.counts.rhs_evals, r.counts.events, r.counts.escapements[0],
              r.counts.escapements[1], r.counts.stick_slip, r.wall_seconds);
  std::printf("ledger E0 %.6e E1 %.6e in %.6e damp %.6e fric %.6e res %.3e rel %.3e\n",
              r.ledger.initial_J, r.ledger.final_J, r.ledger.escapement_in_J,
              r.ledger.damping_out_J, r.ledger.friction_out_J, r.ledger.residual_J(),
              r.ledger.relativeResidual());
  std::printf("final tau %.4f A %.5f %.5f psi %.5f rows %zu env %zu\n", r.final_row.tau,
              r.final_row.A[0], r.final_row.A[1], r.final_row.psi[0], sink.trajectory.size(),
              sink.envelope.size());
  EXPECT_LT(std::abs(r.ledger.relativeResidual()), 1e-6);
}

}  // namespace
}  // namespace metrosync
