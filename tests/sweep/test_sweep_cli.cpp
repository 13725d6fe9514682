// `metrosync sweep` and `metrosync merge` end to end (small slow-flow grids): the same regimes.csv
// for any --jobs, after an interruption and --resume, and from shards merged; exit 2 with nothing
// written for a bad command line; failed points recorded; names and r for three metronomes.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "sim/record/envelope.h"
#include "sim/record/envelope_csv.h"
#include "tests/common/run_metrosync.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using Result = metrosync::testing_support::CommandResult;
using metrosync::testing_support::shellQuote;
using metrosync::testing_support::slurp;

std::string scratch(const std::string& name) {
  return metrosync::testing_support::scratchDir("sweep", name, true);
}

// Runs `[ENV] metrosync ARGS`; captures stdout and stderr.
Result metrosync(const std::string& args, const std::string& env = "") {
  return metrosync::testing_support::runMetrosync(args, {"", env});
}

std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> v;
  std::string l;
  while (std::getline(in, l)) v.push_back(l);
  return v;
}

// cells of a regimes.csv line (no quoted cells in these tests' rows but the message)
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> v;
  std::stringstream ss(line);
  std::string c;
  while (std::getline(ss, c, ',')) v.push_back(c);
  return v;
}

std::string pairRig(const std::string& dir, double tau = 60) {
  return metrosync::testing_support::writePairRig(dir, tau);
}

const std::string kGrid =
    " --vary metronomes.0.start.phi=0:2pi:6:open --vary platform.friction.mu=0:0.8:5";

TEST(SweepCli, SameRegimesCsvForOneAndTwoJobs) {
  const std::string d = scratch("jobs");
  const std::string rig = pairRig(d);
  const Result one = metrosync("sweep " + shellQuote(rig) + kGrid + " --jobs 1 --out " + d + "/j1");
  ASSERT_EQ(one.code, 0) << one.err;
  const Result two =
      metrosync("sweep " + shellQuote(rig) + kGrid + " --jobs 2 -q --out " + d + "/j2");
  ASSERT_EQ(two.code, 0) << two.err;
  EXPECT_EQ(two.out, "");  // --quiet
  EXPECT_NE(one.out.find("30 done"), std::string::npos) << one.out;
  const std::string a = slurp(d + "/j1/regimes.csv"), b = slurp(d + "/j2/regimes.csv");
  EXPECT_EQ(a, b);
  // header, 30 rows sorted by grid index, the key columns first
  const auto l = lines(d + "/j1/regimes.csv");
  ASSERT_EQ(l.size(), 31u);
  EXPECT_EQ(l[0],
            "metronomes.0.start.phi,platform.friction.mu,regime,A_1,A_2,psi_2,r,s,clusters,tau,"
            "complete,index,message");
  for (size_t k = 1; k < l.size(); ++k) EXPECT_EQ(cells(l[k])[11], std::to_string(k - 1));
  // psi0 = 0 on a free platform stays in phase; psi0 = pi at mu = 0.4 stays in antiphase, where
  // the drive |Z| = |A_1 - A_2| is below mu: the platform sticks, `uncoupled` (docs/regimes.md)
  EXPECT_EQ(cells(l[1])[2], "in-phase") << l[1];
  const auto anti = cells(l[1 + 3 * 5 + 2]);
  EXPECT_EQ(anti[0], "3.14159265358979");
  EXPECT_EQ(anti[1], "0.4");
  EXPECT_EQ(anti[2], "uncoupled");
  EXPECT_LT(std::stod(anti[7]), 1.0);  // s = |Z| / mu
  // the manifest and the maps
  const json m = json::parse(slurp(d + "/j1/sweep.json"));
  EXPECT_TRUE(m["complete"].get<bool>());
  EXPECT_EQ(m["points"]["done"], 30);
  EXPECT_EQ(m["grid"]["points"], 30);
  EXPECT_EQ(m["model"], "slow");
  for (const char* f : {"regimes.png", "amplitudes.png", "phases.png", "timings.csv"})
    EXPECT_TRUE(fs::exists(d + "/j1/" + f)) << f;
  for (const auto& e : fs::directory_iterator(d + "/j1"))
    EXPECT_NE(e.path().filename().string()[0], '.') << "left behind: " << e.path();
}

TEST(SweepCli, ResumeAfterAnInterruptionEqualsAnUninterruptedSweep) {
  const std::string d = scratch("resume");
  const std::string rig = pairRig(d);
  ASSERT_EQ(metrosync("sweep " + shellQuote(rig) + kGrid + " -q --out " + d + "/whole").code, 0);
  // the test hook ends the process like kill -9 after 7 points: whole lines only, unsorted
  const Result cut =
      metrosync("sweep " + shellQuote(rig) + kGrid + " -q --jobs 2 --out " + d + "/cut",
                "METROSYNC_SWEEP_STOP_AFTER=7");
  EXPECT_EQ(cut.code, 137) << cut.err;
  auto l = lines(d + "/cut/regimes.csv");
  EXPECT_EQ(l.size(), 8u);
  EXPECT_FALSE(json::parse(slurp(d + "/cut/sweep.json"))["complete"].get<bool>());
  // and a line cut in the middle of its write
  std::ofstream(d + "/cut/regimes.csv", std::ios::app) << "0.5,0.2,in-pha";
  const Result res =
      metrosync("sweep " + shellQuote(rig) + kGrid + " --jobs 2 --resume --out " + d + "/cut");
  ASSERT_EQ(res.code, 0) << res.err;
  EXPECT_NE(res.out.find("23 now, 7 before"), std::string::npos) << res.out;
  EXPECT_NE(res.err.find("cut short"), std::string::npos) << res.err;
  EXPECT_EQ(slurp(d + "/cut/regimes.csv"), slurp(d + "/whole/regimes.csv"));
  // a finished sweep resumes to itself without running anything
  const Result again =
      metrosync("sweep " + shellQuote(rig) + kGrid + " --resume --out " + d + "/cut");
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_NE(again.out.find("0 now, 30 before"), std::string::npos) << again.out;
  EXPECT_EQ(slurp(d + "/cut/regimes.csv"), slurp(d + "/whole/regimes.csv"));
  // without --resume the directory starts over
  const Result over = metrosync("sweep " + shellQuote(rig) + kGrid + " --out " + d + "/cut");
  EXPECT_NE(over.out.find("30 now, 0 before"), std::string::npos) << over.out;
}

TEST(SweepCli, KillNineLosesOnlyThePointsInFlight) {
  const std::string d = scratch("kill");
  const std::string rig = pairRig(d, 5000);  // about 0.1 s a point
  const std::string args =
      "sweep " + shellQuote(rig) + " --vary platform.friction.mu=0:1.5:16 -q --jobs 2 --out ";
  ASSERT_EQ(metrosync(args + d + "/whole").code, 0);
  const std::string cmd = "exec " + shellQuote(METROSYNC_BINARY) + " " + args + d + "/killed";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // wait for 4 rows, then kill -9
  size_t rows = 0;
  const auto t0 = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60)) {
    rows = lines(d + "/killed/regimes.csv").size();
    if (rows >= 5) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the sweep ended before it could be killed";
  const size_t kept = lines(d + "/killed/regimes.csv").size() - 1;
  EXPECT_GE(kept, 4u);
  EXPECT_LT(kept, 16u);
  const Result res = metrosync(args + d + "/killed --resume");
  ASSERT_EQ(res.code, 0) << res.err;
  EXPECT_EQ(slurp(d + "/killed/regimes.csv"), slurp(d + "/whole/regimes.csv"));
}

TEST(SweepCli, ShardsMergedEqualTheWholeSweep) {
  const std::string d = scratch("shards");
  const std::string rig = pairRig(d);
  ASSERT_EQ(metrosync("sweep " + shellQuote(rig) + kGrid + " -q --out " + d + "/whole").code, 0);
  std::string dirs;
  for (int k = 1; k <= 3; ++k) {
    const std::string out = d + "/s" + std::to_string(k);
    const Result r = metrosync("sweep " + shellQuote(rig) + kGrid + " -q --jobs 2 --shard " +
                               std::to_string(k) + "/3 --out " + out);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(lines(out + "/regimes.csv").size(), 11u);  // 10 of the 30 points
    dirs += " " + out;
  }
  const Result m = metrosync("merge" + dirs + " --out " + d + "/merged");
  ASSERT_EQ(m.code, 0) << m.err;
  EXPECT_EQ(slurp(d + "/merged/regimes.csv"), slurp(d + "/whole/regimes.csv"));
  EXPECT_TRUE(json::parse(slurp(d + "/merged/sweep.json"))["complete"].get<bool>());
  EXPECT_TRUE(fs::exists(d + "/merged/regimes.png"));
  // two of three: merged with a warning, incomplete
  const Result part = metrosync("merge " + d + "/s1 " + d + "/s3 --out " + d + "/part");
  ASSERT_EQ(part.code, 0) << part.err;
  EXPECT_NE(part.err.find("10 grid points are in none"), std::string::npos) << part.err;
  EXPECT_FALSE(json::parse(slurp(d + "/part/sweep.json"))["complete"].get<bool>());
  // another grid does not merge, and nothing is written
  ASSERT_EQ(metrosync("sweep " + shellQuote(rig) +
                      " --vary platform.friction.mu=0:0.8:4 -q --shard 2/3 --out " + d + "/other")
                .code,
            0);
  const Result bad = metrosync("merge " + d + "/s1 " + d + "/other --out " + d + "/nope");
  EXPECT_EQ(bad.code, 2) << bad.err;
  EXPECT_NE(bad.err.find("not the same sweep"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(d + "/nope"));
  // and a shard resumed as another shard is refused
  const Result wrong =
      metrosync("sweep " + shellQuote(rig) + kGrid + " -q --shard 2/3 --resume --out " + d + "/s1");
  EXPECT_EQ(wrong.code, 2) << wrong.err;
  EXPECT_NE(wrong.err.find("shard 1/3"), std::string::npos) << wrong.err;
}

TEST(SweepCli, BadCommandLinesExitTwoAndWriteNothing) {
  const std::string d = scratch("bad");
  const std::string rig = pairRig(d);
  struct Case {
    std::string args, says;
  };
  const std::vector<Case> cases = {
      {"--vary platform.friction.mu=0:1", "KEY=FROM:TO:COUNT"},
      {"--vary platform.friction.mu=0:1:zero", "COUNT"},
      {"--vary platform.friction.mu=0:1:3:closed", "open"},
      {"--vary platform.friction.muu=0:1:3", "muu"},            // unknown key
      {"--vary metronomes.5.start.phi=0:1:3", "metronomes.5"},  // no such metronome
      {"--vary platform.friction.mu=-1:1:3", "must be >= 0"},   // a bad value at point 0
      {"--vary metronomes.0.alpha=0:1:3", "alpha"},             // 0 for metronome 1
      // three axes are an N-D grid (test_sweep_axes.cpp): here a bad key of one of them
      {"--vary a=0:1:2 --vary b=0:1:2 --vary c=0:1:2", "a: unknown key"},
      {"--vary platform.friction.mu=0:1:2 --vary platform.friction.mu=0:1:3", "twice"},
      {"--vary platform.friction.mu=0:1:3 --shard 4/3", "--shard"},
      {"--vary platform.friction.mu=0:1:3 --jobs 0", "jobs"},
      {"--vary platform.friction.mu=0:1:3 --model fast", "model"},
      {"--vary platform.friction.mu=0:1:3 --set simulation.tau=-1", "simulation.tau"},
      {"", "--vary"},
  };
  for (const auto& c : cases) {
    const std::string out = d + "/out";
    const Result r = metrosync("sweep " + shellQuote(rig) + " " + c.args + " --out " + out);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("metrosync: error: ", 0), 0u) << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
  // a bad value at the grid's end stops it before any point runs (the grid is checked at its
  // corners, tools/cli/sweep.cpp checkGrid: the loader's checks are ranges)
  const Result mid = metrosync("sweep " + shellQuote(rig) +
                               " --vary metronomes.1.start.A=1:-1:5 --out " + d + "/out");
  EXPECT_EQ(mid.code, 2) << mid.err;
  EXPECT_NE(mid.err.find("metronomes.1.start.A=-1"), std::string::npos) << mid.err;
  EXPECT_FALSE(fs::exists(d + "/out"));
  // --resume of another sweep: refused, and the directory left as it was
  ASSERT_EQ(metrosync("sweep " + shellQuote(rig) + " --vary platform.friction.mu=0:1:3 -q --out " +
                      d + "/done")
                .code,
            0);
  const std::string before = slurp(d + "/done/regimes.csv");
  const Result other =
      metrosync("sweep " + shellQuote(rig) + " --vary platform.friction.mu=0:1:4 --resume --out " +
                d + "/done");
  EXPECT_EQ(other.code, 2) << other.err;
  EXPECT_NE(other.err.find("another sweep"), std::string::npos) << other.err;
  EXPECT_EQ(slurp(d + "/done/regimes.csv"), before);
}

TEST(SweepCli, FailedPointsAreRecordedAndTheSweepGoesOn) {
  const std::string d = scratch("failed");
  const std::string rig = pairRig(d);
  const Result r = metrosync(
      "sweep " + shellQuote(rig) + " --vary platform.friction.mu=0:1:6 --jobs 2 --out " + d + "/o",
      "METROSYNC_SWEEP_FAIL_AT=1,4");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("2 grid points failed"), std::string::npos) << r.err;
  const auto l = lines(d + "/o/regimes.csv");
  ASSERT_EQ(l.size(), 7u);
  for (int g = 0; g < 6; ++g) {
    const auto c = cells(l[1 + g]);
    const bool failed = g == 1 || g == 4;
    EXPECT_EQ(c[1] == "failed", failed) << l[1 + g];
    EXPECT_EQ(c[9], failed ? "0" : "1") << l[1 + g];
    EXPECT_EQ(l[1 + g].find("METROSYNC_SWEEP_FAIL_AT") != std::string::npos, failed);
  }
  EXPECT_EQ(json::parse(slurp(d + "/o/sweep.json"))["points"]["failed"], 2);
}

TEST(SweepCli, ThreeMetronomesAreNamedByClustersWithTheirOrderParameter) {
  // identical metronomes on a platform held still keep their phases: metronome 2 at 2 pi/3,
  // metronome 3 at 0, 2 pi/3, 4 pi/3
  const std::string d = scratch("three");
  const std::string rig = d + "/three.yaml";
  std::ofstream(rig)
      << "units: scaled\nname: three\nepsilon: 0.05\n"
         "platform:\n  friction: {law: fixed}\nmetronomes:\n"
         "  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: 2.9, phi: 0}}\n"
         "  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: 2.9, phi: 2.0943951023931957}}\n"
         "  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: 2.9, phi: 0}}\n"
         "simulation:\n  tau: 40\n";
  const Result r = metrosync("sweep " + shellQuote(rig) +
                             " --vary metronomes.2.start.phi=0:2pi:3:open -q --out " + d + "/o");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto l = lines(d + "/o/regimes.csv");
  ASSERT_EQ(l.size(), 4u);
  EXPECT_EQ(l[0],
            "metronomes.2.start.phi,regime,A_1,A_2,A_3,psi_2,psi_3,r,s,clusters,tau,complete,"
            "index,message");
  const auto a = cells(l[1]), b = cells(l[2]), c = cells(l[3]);
  // a platform held still couples nothing: `uncoupled` (docs/regimes.md), the clusters column
  // still says how the phases sit
  EXPECT_EQ(a[1], "uncoupled");
  EXPECT_EQ(b[1], "uncoupled");
  EXPECT_EQ(c[1], "uncoupled");
  EXPECT_EQ(a[9], "2+1");                      // 1 and 3 together
  EXPECT_EQ(b[9], "2+1");                      // 2 and 3 together
  EXPECT_EQ(c[9], "1x3");                      // a splay state
  EXPECT_NEAR(std::stod(a[7]), 0.5774, 1e-3);  // |2 + e^{i 2 pi/3}| / 3 = 1/sqrt(3)
  EXPECT_NEAR(std::stod(c[7]), 0.0, 1e-6);
  EXPECT_EQ(a[8], "");  // s: no Coulomb platform (no value: empty)
  EXPECT_TRUE(fs::exists(d + "/o/order.png"));
}

TEST(SweepCli, BothModelsWriteTheOrderParameterInEnvelopeCsv) {
  const std::string d = scratch("envr");
  const std::string rig = d + "/four.yaml";
  std::ofstream(rig) << "units: scaled\nname: four\nepsilon: 0.05\n"
                        "platform:\n  friction: {law: fixed}\nmetronomes:\n"
                        "  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: 2.9, phi: 0.3}}\n"
                        "  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: 2.9, phi: 0.3}}\n"
                        "  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: 2.9, phi: 0.3}}\n"
                        "simulation:\n  tau: 1.5\n";
  for (const char* model : {"full", "slow"}) {
    for (const char* start : {"in-phase", "splay"}) {
      const std::string out = d + "/" + model + "-" + start;
      std::string sets;
      if (std::string(start) == "splay")
        sets =
            " --set metronomes.1.start.phi=2.3943951023931958"
            " --set metronomes.2.start.phi=4.4887902047863905";
      const Result r =
          metrosync("run " + shellQuote(rig) + " --model " + model + sets + " -q --out " + out);
      ASSERT_EQ(r.code, 0) << r.err;
      EXPECT_EQ(lines(out + "/envelope.csv")[0], "tau,A_1,A_2,A_3,psi_2,psi_3,r");
      const auto rows = metrosync::readEnvelopeCsv(out + "/envelope.csv");
      ASSERT_GT(rows.size(), 3u);
      for (const auto& row : rows) {
        if (std::string(start) == "in-phase")
          EXPECT_NEAR(row.r, 1.0, 1e-9) << model << " tau " << row.tau;
        else
          EXPECT_LT(row.r, 0.02) << model << " tau " << row.tau;
      }
    }
  }
}

}  // namespace
