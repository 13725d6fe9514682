// `mpirun -np 2 metrosync-mpi sweep` (and `metrosync sweep`, which hands over to it) end to end
// (docs/cluster.md): the regimes.csv of the serial `metrosync sweep --jobs 1`, bit for bit; a rank
// killed with SIGKILL, or the whole job ended like kill -9 after some rows, then --resume under
// MPI: the uninterrupted sweep's regimes.csv, no row lost or doubled; a bad command line exits 2
// with nothing written and no rank left waiting.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "tests/common/run_metrosync.h"

namespace {

namespace fs = std::filesystem;
using metrosync::testing_support::CommandResult;
using metrosync::testing_support::runMetrosync;
using metrosync::testing_support::shellQuote;
using metrosync::testing_support::slurp;

std::string scratch(const std::string& name) {
  return metrosync::testing_support::scratchDir("mpi", name, true);
}

// `[ENV] mpirun -np RANKS metrosync-mpi ARGS` (oversubscribed: this machine may have fewer
// cores than ranks); captures stdout and stderr.
CommandResult mpiMetrosync(int ranks, const std::string& args, const std::string& env = "",
                           std::string binary = METROSYNC_MPI_BINARY) {
  // a fault variable: the build with the tests' fault hooks (tools/cli/fault_hooks.h)
  if (binary == METROSYNC_MPI_BINARY && metrosync::testing_support::setsFaults(env))
    binary = METROSYNC_MPI_FAULTS_BINARY;
  return metrosync::testing_support::runCommand(
      env + " " + shellQuote(METROSYNC_MPIEXEC) + " -np " + std::to_string(ranks) +
      " --oversubscribe --allow-run-as-root " + shellQuote(binary) + " " + args);
}

std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> v;
  std::string l;
  while (std::getline(in, l)) v.push_back(l);
  return v;
}

// The paper's experiment in scaled variables (yaml/rigs/experiment-map.yaml), shorter: a 12 x 12
// slow-flow map over the start phase and mu holds in-phase, antiphase, suppression and death.
std::string pairRig(const std::string& dir, double tau) {
  return metrosync::testing_support::writePairRig(dir, tau);
}

const std::string kMap =
    " --vary metronomes.0.start.phi=0:2pi:12:open --vary platform.friction.mu=0:0.8:12";

TEST(SweepMpi, TwoRanksWriteTheSerialRegimesCsvBitForBit) {
  const std::string d = scratch("same");
  const std::string sweep = "sweep " + shellQuote(pairRig(d, 60)) + kMap;
  const CommandResult serial =
      runMetrosync(sweep + " --jobs 1 -q --no-plot --out " + d + "/serial");
  ASSERT_EQ(serial.code, 0) << serial.err;
  const std::string want = slurp(d + "/serial/regimes.csv");
  ASSERT_EQ(lines(d + "/serial/regimes.csv").size(), 145u);
  // the regimes differ over the map (else equal files would prove little)
  const nlohmann::json s = nlohmann::json::parse(slurp(d + "/serial/sweep.json"));
  EXPECT_GE(s["regimes"].size(), 3u) << s["regimes"];

  // metrosync-mpi with 1 and 2 threads a rank, and plain metrosync, which hands itself over to
  // metrosync-mpi when an MPI launcher started it as one of several ranks
  for (const auto& [binary, jobs] : {std::pair<std::string, std::string>{METROSYNC_MPI_BINARY, "1"},
                                     {METROSYNC_MPI_BINARY, "2"},
                                     {METROSYNC_BINARY, "1"}}) {
    const std::string out = d + "/" + fs::path(binary).filename().string() + "-jobs" + jobs;
    const CommandResult mpi =
        mpiMetrosync(2, sweep + " --jobs " + jobs + " --out " + out, "", binary);
    ASSERT_EQ(mpi.code, 0) << mpi.err;
    EXPECT_EQ(slurp(out + "/regimes.csv"), want) << binary << " --jobs " << jobs;
    EXPECT_NE(mpi.out.find("144 done (144 now, 0 before)"), std::string::npos) << mpi.out;
    EXPECT_NE(mpi.out.find("on 2 MPI ranks"), std::string::npos) << mpi.out;
    const nlohmann::json m = nlohmann::json::parse(slurp(out + "/sweep.json"));
    EXPECT_TRUE(m["complete"].get<bool>());
    EXPECT_EQ(m["mpi_ranks"], 2);
    EXPECT_EQ(m["regimes"], s["regimes"]);
    EXPECT_TRUE(fs::exists(out + "/regimes.png"));  // rank 0 draws the maps
    EXPECT_EQ(lines(out + "/timings.csv").size(), 145u);
  }
}

// Points of about 20 ms, so that the job is cut early; the reference is the serial sweep.
struct Interrupted {
  std::string d, sweep;
  explicit Interrupted(const std::string& name)
      : d(scratch(name)), sweep("sweep " + shellQuote(pairRig(d, 1500)) + kMap + " -q --no-plot") {
    const CommandResult whole = runMetrosync(sweep + " --jobs 2 --out " + d + "/whole");
    EXPECT_EQ(whole.code, 0) << whole.err;
  }
  // Resumes DIR under MPI and checks it against the uninterrupted sweep.
  void resumeAndCompare(const std::string& dir, size_t kept_rows) const {
    const CommandResult res = mpiMetrosync(2, sweep + " --jobs 1 --resume --out " + dir);
    ASSERT_EQ(res.code, 0) << res.err;
    EXPECT_EQ(slurp(dir + "/regimes.csv"), slurp(d + "/whole/regimes.csv"));
    const nlohmann::json m = nlohmann::json::parse(slurp(dir + "/sweep.json"));
    EXPECT_EQ(m["points"]["run_now"].get<long>(), 144 - static_cast<long>(kept_rows));
  }
};

TEST(SweepMpi, AWorkerKilledWithSigkillLosesOnlyItsPointsInFlight) {
  const Interrupted run("killrank");
  const std::string dir = run.d + "/killed";
  // rank 1 raises SIGKILL after its 5th point, before reporting it; mpirun then ends the job
  const CommandResult cut =
      mpiMetrosync(2, run.sweep + " --jobs 1 --out " + dir, "METROSYNC_MPI_KILL_AFTER=1:5");
  EXPECT_NE(cut.code, 0) << "the worker was never given 5 points";
  const size_t kept = lines(dir + "/regimes.csv").size() - 1;
  EXPECT_GE(kept, 4u);  // rank 1's first 4 points at least reached rank 0
  EXPECT_LT(kept, 144u);
  std::set<std::string> seen;
  for (const auto& l : lines(dir + "/regimes.csv")) EXPECT_TRUE(seen.insert(l).second) << l;
  run.resumeAndCompare(dir, kept);
}

TEST(SweepMpi, TheWholeJobEndedAfterSomeRowsResumesUnderMpi) {
  const Interrupted run("killjob");
  const std::string dir = run.d + "/cut";
  // rank 0 ends like kill -9 right after writing its 30th row (the existing test hook)
  const CommandResult cut =
      mpiMetrosync(2, run.sweep + " --jobs 1 --out " + dir, "METROSYNC_SWEEP_STOP_AFTER=30");
  EXPECT_NE(cut.code, 0);
  EXPECT_EQ(lines(dir + "/regimes.csv").size(), 31u);
  EXPECT_FALSE(nlohmann::json::parse(slurp(dir + "/sweep.json"))["complete"].get<bool>());
  run.resumeAndCompare(dir, 30);
}

TEST(SweepMpi, BadInputExitsTwoOnEveryRankWithNothingWritten) {
  const std::string d = scratch("bad");
  const std::string rig = shellQuote(pairRig(d, 60));
  const CommandResult key =
      mpiMetrosync(2, "sweep " + rig + " --vary platform.friction.nope=0:1:3 --out " + d + "/o");
  EXPECT_EQ(key.code, 2) << key.err;
  EXPECT_NE(key.err.find("nope"), std::string::npos) << key.err;
  const CommandResult vary = mpiMetrosync(2, "sweep " + rig + " --vary mu --out " + d + "/o");
  EXPECT_EQ(vary.code, 2) << vary.err;
  // rank 0 alone says what is wrong (the worker's parse error would only repeat it)
  EXPECT_EQ(vary.err.find("metrosync: error"), vary.err.rfind("metrosync: error")) << vary.err;
  EXPECT_FALSE(fs::exists(d + "/o"));
}

}  // namespace

namespace {

// `metrosync basin` over 2 ranks draws the same samples and runs them to the same rows as the
// serial basin (--jobs 1): basin.csv bit for bit, and the same fractions in basin.json.
TEST(BasinMpi, TwoRanksWriteTheSerialBasinCsvBitForBit) {
  const std::string d = scratch("basin");
  const std::string basin = "basin " + shellQuote(pairRig(d, 60)) +
                            " --random metronomes.0.start.phi=0:2pi --random "
                            "platform.friction.mu=0:0.8 --samples 60 --seed 7 -q --no-plot";
  const CommandResult serial = runMetrosync(basin + " --jobs 1 --out " + d + "/serial");
  ASSERT_EQ(serial.code, 0) << serial.err;
  const std::string want = slurp(d + "/serial/basin.csv");
  ASSERT_EQ(lines(d + "/serial/basin.csv").size(), 61u);
  const nlohmann::json s = nlohmann::json::parse(slurp(d + "/serial/basin.json"));
  for (const std::string jobs : {"1", "2"}) {
    const std::string out = d + "/mpi-jobs" + jobs;
    const CommandResult mpi = mpiMetrosync(2, basin + " --jobs " + jobs + " --out " + out);
    ASSERT_EQ(mpi.code, 0) << mpi.err;
    EXPECT_EQ(slurp(out + "/basin.csv"), want) << "--jobs " << jobs;
    const nlohmann::json m = nlohmann::json::parse(slurp(out + "/basin.json"));
    EXPECT_EQ(m["fractions"], s["fractions"]);
  }
}

}  // namespace
