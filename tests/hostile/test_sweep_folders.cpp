// Issue 17, item 7: merge refuses a source given twice and an --out that is one of its sources;
// a sweep holds a lock on its folder, so that a second sweep (or merge) into it exits 2 naming the
// process that holds it, and a lock left by a killed sweep is taken over.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include "tests/common/run_metrosync.h"
#include "tools/report/folder_lock.h"

namespace metrosync {
namespace {

namespace fs = std::filesystem;
using testing_support::CommandResult;
using testing_support::runMetrosync;
using testing_support::scratchDir;
using testing_support::shellQuote;
using testing_support::slurp;

const std::string kRig = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/experiment.yaml";

CommandResult shardOf(const std::string& dir, const std::string& shard) {
  return runMetrosync("sweep " + shellQuote(kRig) +
                      " --vary platform.friction.mu=0.01:0.3:4 -q --shard " + shard + " --out " +
                      shellQuote(dir));
}

TEST(SweepFolders, MergeRefusesASourceGivenTwice) {
  const std::string d = scratchDir("folders", "twice", true);
  ASSERT_EQ(shardOf(d + "/s1", "1/2").code, 0);
  ASSERT_EQ(shardOf(d + "/s2", "2/2").code, 0);
  fs::copy(d + "/s1", d + "/s1-copy", fs::copy_options::recursive);
  // the same folder under two names, and the same shard from a copy
  for (const std::string& second : {d + "/s1", d + "/./s1", d + "/s1-copy"}) {
    const CommandResult r =
        runMetrosync("merge " + shellQuote(d + "/s1") + " " + shellQuote(second) + " " +
                     shellQuote(d + "/s2") + " -q --out " + shellQuote(d + "/m"));
    EXPECT_EQ(r.code, 2) << second << "\n" << r.err;
    EXPECT_NE(r.err.find("given twice"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(d + "/m"));
  }
  EXPECT_EQ(runMetrosync("merge " + shellQuote(d + "/s1") + " " + shellQuote(d + "/s2") +
                         " -q --out " + shellQuote(d + "/m"))
                .code,
            0);
}

TEST(SweepFolders, MergeRefusesAnOutThatIsASource) {
  const std::string d = scratchDir("folders", "outsource", true);
  ASSERT_EQ(shardOf(d + "/s1", "1/2").code, 0);
  ASSERT_EQ(shardOf(d + "/s2", "2/2").code, 0);
  const std::string regimes = slurp(d + "/s1/regimes.csv"), json = slurp(d + "/s1/sweep.json");
  const CommandResult r =
      runMetrosync("merge " + shellQuote(d + "/s1") + " " + shellQuote(d + "/s2") + " -q --out " +
                   shellQuote(d + "/s1"));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("one of the sources"), std::string::npos) << r.err;
  // the shard is untouched: it can still be resumed and merged
  EXPECT_EQ(slurp(d + "/s1/regimes.csv"), regimes);
  EXPECT_EQ(slurp(d + "/s1/sweep.json"), json);
  EXPECT_TRUE(fs::exists(d + "/s1/timings.csv"));
}

TEST(SweepFolders, ASecondSweepIntoAFolderInUseExitsTwoNamingTheHolder) {
  const std::string d = scratchDir("folders", "locked", true);
  const std::string out = d + "/out";
  fs::create_directories(out);
  {
    FolderLock held(out, "a test holding the folder");
    const CommandResult r = shardOf(out, "1/1");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("pid " + std::to_string(::getpid())), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("a test holding the folder"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out + "/regimes.csv"));
    const CommandResult m =
        runMetrosync("merge " + shellQuote(d + "/none") + " --out " + shellQuote(out));
    EXPECT_EQ(m.code, 2) << m.err;
  }
  EXPECT_EQ(shardOf(out, "1/1").code, 0) << "the lock is released with its holder";
  EXPECT_FALSE(fs::exists(out + "/" + FolderLock::kFileName)) << "removed when the sweep ends";
}

TEST(SweepFolders, ALockLeftByAKilledSweepIsTakenOver) {
  const std::string out = scratchDir("folders", "stale", true) + "/out";
  // the sweep dies (exit 137, as kill -9) after its first point: its lock file stays behind
  const CommandResult killed = runMetrosync(
      "sweep " + shellQuote(kRig) + " --vary platform.friction.mu=0.01:0.3:4 -q --jobs 1 --out " +
          shellQuote(out),
      {"", "METROSYNC_SWEEP_STOP_AFTER=1"});
  ASSERT_EQ(killed.code, 137) << killed.err;
  ASSERT_TRUE(fs::exists(out + "/" + FolderLock::kFileName));
  const CommandResult resumed =
      runMetrosync("sweep " + shellQuote(kRig) +
                   " --vary platform.friction.mu=0.01:0.3:4 -q --resume --out " + shellQuote(out));
  EXPECT_EQ(resumed.code, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("took over the lock"), std::string::npos) << resumed.err;
}

}  // namespace
}  // namespace metrosync
