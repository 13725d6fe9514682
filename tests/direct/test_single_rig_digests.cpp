// Every shipped single-platform rig (yaml/rigs, yaml/rigs/paper, yaml/rigs/bench, and the network
// of one board-on-springs.yaml) writes bit for bit the files of the build before issue 24's one
// model (tests/direct/reference/single_rigs.txt, recorded by
// `tools/reference/single_rig_digests.sh write METROSYNC tests/direct/reference/single_rigs.txt`
// from that build): its trajectory, envelope and events files and its summary's results.
#include <gtest/gtest.h>

#include <string>

#include "tests/common/run_metrosync.h"

namespace metrosync {
namespace {

using testing_support::runCommand;
using testing_support::shellQuote;

TEST(SingleRigDigests, EveryShippedSingleRigIsBitForBitThePreviousBuilds) {
  const std::string src = METROSYNC_SOURCE_DIR;
  const auto r = runCommand(shellQuote(src + "/tools/reference/single_rig_digests.sh") + " check " +
                            shellQuote(METROSYNC_BINARY) + " " +
                            shellQuote(src + "/tests/direct/reference/single_rigs.txt"));
  EXPECT_EQ(r.code, 0) << r.out << r.err;
}

}  // namespace
}  // namespace metrosync
