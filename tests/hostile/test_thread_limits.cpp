// Issue 29: worker threads. A sweep or basin never starts more threads than it has points, and a
// thread the system refuses to start (RLIMIT_NPROC, run_threads_limited.sh) is no abort: the
// work runs on the threads that started, the files come out whole and sorted.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>

#include "sim/parallel/worker_pool.h"
#include "tests/hostile/hostile_support.h"

namespace metrosync::hostile {
namespace {

namespace fs = std::filesystem;
using testing_support::csvRows;
using testing_support::scratchDir;
using testing_support::slurp;

const std::string kTwelvePoints = "sweep --vary platform.friction.mu=0.01:0.3:12 -q --no-plot";

// `metrosync ARGS --out OUT` with at most `nproc` processes and threads for its user.
CommandResult runUnderThreadLimit(int nproc, const std::string& args, const std::string& out) {
  testing_support::RunIn in;
  in.env = "timeout -s KILL 20 " +
           shellQuote(sourceDir() + "/tests/hostile/run_threads_limited.sh") + " " +
           std::to_string(nproc);
  return runMetrosync(args + " --out " + shellQuote(out), in);
}

bool haveLimitTools() {
  return std::system("command -v prlimit >/dev/null && command -v setpriv >/dev/null") == 0;
}

// The folder made writable for `nobody` (run_threads_limited.sh runs as it under root).
std::string sharedScratch(const std::string& name) {
  const std::string d = scratchDir("threads", name, true);
  fs::permissions(d, fs::perms::all);
  return d;
}

int jobsIn(const std::string& json_path) {
  const std::string j = slurp(json_path);
  const size_t at = j.find("\"jobs\": ");
  return at == std::string::npos ? -1 : std::stoi(j.substr(at + 8));
}

TEST(ThreadLimits, ASweepUnderAThreadLimitRunsOnTheThreadsThatStart) {
  if (!haveLimitTools()) GTEST_SKIP() << "prlimit or setpriv missing";
  for (int nproc : {1, 3}) {
    const std::string out = sharedScratch("sweep" + std::to_string(nproc)) + "/out";
    const CommandResult r = runUnderThreadLimit(nproc, kTwelvePoints + " --jobs 8", out);
    ASSERT_EQ(r.code, 0) << "nproc " << nproc << "\n" << r.err;  // main: 134, an abort
    EXPECT_EQ(r.err.find("terminate"), std::string::npos) << r.err;
    const auto rows = csvRows(out + "/regimes.csv");
    ASSERT_EQ(rows.size(), 13u);
    for (size_t k = 1; k < rows.size(); ++k)  // sorted: the index column counts up
      EXPECT_EQ(rows[k][rows[0].size() - 2], std::to_string(k - 1)) << k;
    EXPECT_GE(jobsIn(out + "/sweep.json"), 1);
    EXPECT_LE(jobsIn(out + "/sweep.json"), nproc);
    EXPECT_NE(slurp(out + "/sweep.json").find("\"complete\": true"), std::string::npos);
    EXPECT_FALSE(fs::exists(out + "/.metrosync.lock"));
  }
}

TEST(ThreadLimits, ABasinUnderAThreadLimitRunsOnTheThreadsThatStart) {
  if (!haveLimitTools()) GTEST_SKIP() << "prlimit or setpriv missing";
  const std::string out = sharedScratch("basin") + "/out";
  const CommandResult r = runUnderThreadLimit(
      1,
      "basin " + shellQuote(sourceDir() + "/yaml/rigs/experiment-map.yaml") +
          " --random metronomes.0.start.phi=0:2pi --samples 6 --jobs 4096 -q --no-plot",
      out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(csvRows(out + "/basin.csv").size(), 7u);
  EXPECT_EQ(jobsIn(out + "/basin.json"), 1);
}

// --jobs 200 for 12 points: 12 threads, not 200 (main started all 200). Without the 200 MB limit
// of runLimited: under it, each thread's 8 MB stack is address space, and fewer than 12 start.
TEST(ThreadLimits, NeverMoreThreadsThanPoints) {
  const std::string d = scratchDir("threads", "many", true);
  auto run = [](const std::string& args, const std::string& out) {
    return runMetrosync(args + " --out " + shellQuote(out));
  };
  ASSERT_EQ(run(kTwelvePoints + " --jobs 200", d + "/sweep").code, 0);
  EXPECT_EQ(jobsIn(d + "/sweep/sweep.json"), 12);
  ASSERT_EQ(run("basin " + shellQuote(sourceDir() + "/yaml/rigs/experiment-map.yaml") +
                    " --random metronomes.0.start.phi=0:2pi --samples 3 --jobs 4096 -q "
                    "--no-plot",
                d + "/basin")
                .code,
            0);
  EXPECT_EQ(jobsIn(d + "/basin/basin.json"), 3);
}

TEST(WorkerPool, EveryTaskOnceAndTheFirstErrorBack) {
  EXPECT_EQ(workerCount(200, 12), 12);
  EXPECT_EQ(workerCount(3, 0), 1);
  EXPECT_GE(workerCount(0, 1000), 1);  // the cores
  std::vector<std::atomic<int>> seen(1000);
  const int threads = parallelFor(1000, 4, [&](long k) { ++seen[k]; });
  EXPECT_GE(threads, 1);
  EXPECT_LE(threads, 4);
  for (const auto& s : seen) EXPECT_EQ(s.load(), 1);
  // The failing task is reached before any task past 500 can run: every other task waits for it
  // to start and then takes 1 ms, so reaching 500 would take the other two workers ~0.25 s (a
  // loaded machine may deschedule a worker for a while; it cannot make 490 tasks run in the
  // microseconds between the throw and the pool seeing it).
  std::atomic<long> after{0};
  std::atomic<bool> failing{false};
  EXPECT_THROW(parallelFor(1000, 3,
                           [&](long k) {
                             if (k == 10) {
                               failing = true;
                               throw std::runtime_error("boom");
                             }
                             while (k > 10 && !failing) std::this_thread::yield();
                             std::this_thread::sleep_for(std::chrono::milliseconds(1));
                             if (k > 500) ++after;
                           }),
               std::runtime_error);
  EXPECT_LT(after.load(), 490);  // no new task once one failed (a few may be in flight)
  // a stop request ends the loop
  std::atomic<long> ran{0};
  parallelFor(
      100000, 2, [&](long) { ++ran; }, [&] { return ran.load() >= 10; });
  EXPECT_LT(ran.load(), 100);
}

}  // namespace
}  // namespace metrosync::hostile
