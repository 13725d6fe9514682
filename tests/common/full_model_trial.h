// A single rig's run on either full-model engine into memory, and the check that two runs are
// the same bits (steps, events, every trajectory row): the friction laws' tests compare a law at
// its limit with the law it reduces to (tests/direct, tests/simbody).
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "sim/engines/direct/direct_engine.h"
#include "sim/engines/simbody/simbody_engine.h"

namespace metrosync::testing_support {

struct Trial {
  RunReport report;
  MemorySink sink;
};

// `engine` is "direct" or "simbody".
inline Trial runOn(const std::string& engine, const Rig& rig) {
  Trial r;
  r.report =
      engine == "direct" ? runDirectModel(rig, r.sink) : runSimbody(networkOfOne(rig), r.sink);
  return r;
}

inline void expectSameBits(const Trial& a, const Trial& b) {
  ASSERT_TRUE(a.report.complete && b.report.complete);
  EXPECT_EQ(a.report.counts.steps, b.report.counts.steps);
  EXPECT_EQ(a.report.counts.events, b.report.counts.events);
  EXPECT_EQ(a.report.counts.stick_slip, b.report.counts.stick_slip);
  EXPECT_EQ(a.report.counts.slip_reversals, b.report.counts.slip_reversals);
  EXPECT_EQ(a.report.counts.escapements, b.report.counts.escapements);
  EXPECT_EQ(a.sink.trajectory, b.sink.trajectory);  // every row, bit for bit
  EXPECT_EQ(a.sink.events, b.sink.events);
}

}  // namespace metrosync::testing_support
