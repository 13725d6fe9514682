// Issue 17, item 8, the sweep's share: a corrupted sweep.json is named in the message (whatever is
// wrong with it), and merge, which runs nothing, does not promise that a dropped point "runs
// again".
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/hostile/hostile_support.h"

namespace metrosync::hostile {
namespace {

namespace fs = std::filesystem;

// A small finished sweep to corrupt: three slow-flow points.
std::string smallSweep(const std::string& name) {
  const std::string dir = testing_support::scratchDir("hostile", name);
  const CommandResult r =
      runMetrosync("sweep " + shellQuote(sourceDir() + "/yaml/rigs/experiment.yaml") +
                   " --vary platform.friction.mu=0.01:0.3:3 -q --out " + shellQuote(dir));
  EXPECT_EQ(r.code, 0) << r.err;
  return dir;
}

TEST(HostileSweepMessages, CorruptedSweepJsonIsNamedForResumeAndMerge) {
  const std::string dir = smallSweep("corrupt_manifest");
  // valid JSON, but not a manifest: the parser does not fail, the manifest's reader does
  std::ofstream(dir + "/sweep.json") << "{\"command\": \"sweep\"}\n";
  const std::string json = dir + "/sweep.json";
  const CommandResult merge =
      runMetrosync("merge " + shellQuote(dir) + " --out " + shellQuote(dir + "-merged"));
  EXPECT_EQ(merge.code, 2) << merge.err;
  EXPECT_NE(merge.err.find(json + ": "), std::string::npos) << merge.err;
  EXPECT_FALSE(fs::exists(dir + "-merged"));
  const CommandResult resume =
      runMetrosync("sweep " + shellQuote(sourceDir() + "/yaml/rigs/experiment.yaml") +
                   " --vary platform.friction.mu=0.01:0.3:3 -q --resume --out " + shellQuote(dir));
  EXPECT_EQ(resume.code, 2) << resume.err;
  EXPECT_NE(resume.err.find(json + ": "), std::string::npos) << resume.err;
}

TEST(HostileSweepMessages, MergeSaysADroppedLineLeavesThePointOut) {
  const std::string dir = smallSweep("bad_line");
  std::ofstream(dir + "/regimes.csv", std::ios::app) << "0.5,in-phase,not,a,row\n";
  const CommandResult merge =
      runMetrosync("merge " + shellQuote(dir) + " -q --out " + shellQuote(dir + "-merged"));
  EXPECT_EQ(merge.code, 0) << merge.err;
  EXPECT_NE(merge.err.find("merge leaves the point out"), std::string::npos) << merge.err;
  EXPECT_EQ(merge.err.find("runs again"), std::string::npos) << merge.err;
}

}  // namespace
}  // namespace metrosync::hostile
