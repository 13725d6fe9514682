// Determinism (issue 10, Box2D's determinism hash): the same rig gives bit-identical trajectories
// run after run, alone or beside other runs on other threads, and a sweep's results do not depend
// on --jobs. Every double the engine hands its sink goes into a 64-bit FNV-1a hash of its bytes;
// the hash is checked to see a perturbation of the start in the last bits, so that an equal hash
// is not equal because it saw nothing.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "sim/engines/engine.h"
#include "tests/common/run_metrosync.h"
#include "yaml/rig_loader.h"

namespace {

using metrosync::testing_support::runMetrosync;
using metrosync::testing_support::scratchDir;
using metrosync::testing_support::shellQuote;
using metrosync::testing_support::slurp;

// FNV-1a, 64 bits, over the exact bytes of every value the engine emits.
struct HashSink : metrosync::RunSink {
  std::uint64_t h = 1469598103934665603ull;
  long values = 0;
  void bytes(const void* p, size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (size_t k = 0; k < n; ++k) h = (h ^ c[k]) * 1099511628211ull;
  }
  void doubles(const std::vector<double>& v) {
    bytes(v.data(), v.size() * sizeof(double));
    values += static_cast<long>(v.size());
  }
  void trajectoryRow(const std::vector<double>& row) override { doubles(row); }
  void envelopeRow(const metrosync::EnvelopeRow& row) override {
    doubles({row.tau, row.r});
    doubles(row.A);
    doubles(row.psi);
  }
  void eventRow(const char* kind, const std::vector<double>& row) override {
    bytes(kind, std::strlen(kind));
    doubles(row);
  }
};

struct Case {
  std::string engine;
  std::vector<std::string> sets;
};

// Short runs that still hold ticks and stick-slip switches (the default rig: the paper's
// experiment on low-friction rollers, started near antiphase).
std::vector<Case> cases() {
  return {{"direct", {"simulation.duration=3"}},
          {"direct", {"simulation.duration=3", "platform.friction.mu=0.002"}},
          {"simbody", {"simulation.duration=1"}},
          {"slowflow", {"simulation.duration=30"}}};
}

HashSink runCase(const Case& c, const std::vector<std::string>& more = {}) {
  std::vector<std::string> sets = c.sets;
  sets.insert(sets.end(), more.begin(), more.end());
  HashSink sink;
  const metrosync::RunReport rep =
      metrosync::findEngine(c.engine)->run(metrosync::defaultRig(sets), sink);
  EXPECT_TRUE(rep.complete) << c.engine << ": " << rep.failure;
  return sink;
}

TEST(Determinism, SameRigSameBitsRunAfterRun) {
  for (const Case& c : cases()) {
    const HashSink a = runCase(c), b = runCase(c);
    EXPECT_GT(a.values, 100) << c.engine;
    EXPECT_EQ(a.values, b.values) << c.engine;
    EXPECT_EQ(a.h, b.h) << c.engine;
    // the hash sees the last bits of the start: angle_2 = -0.785 moved by one ulp
    const HashSink moved = runCase(c, {"metronomes.1.start.angle=-0.7850000000000001"});
    EXPECT_NE(a.h, moved.h) << c.engine;
  }
}

TEST(Determinism, SameBitsOnTwoThreads) {
  const std::vector<Case> cs = cases();
  std::vector<std::uint64_t> alone, together(cs.size());
  for (const Case& c : cs) alone.push_back(runCase(c).h);
  // two threads, each running every other case, at the same time
  auto worker = [&](size_t first) {
    for (size_t k = first; k < cs.size(); k += 2) together[k] = runCase(cs[k]).h;
  };
  std::thread t0(worker, 0), t1(worker, 1);
  t0.join();
  t1.join();
  for (size_t k = 0; k < cs.size(); ++k) EXPECT_EQ(alone[k], together[k]) << cs[k].engine;
}

// The files as the user gets them: trajectory.csv twice, and regimes.csv under --jobs 1 and 2.
TEST(Determinism, FilesDoNotDependOnTheRunOrJobs) {
  const std::string d = scratchDir("determinism", "files", true);
  const std::string run = "run -q --set simulation.duration=3 --out ";
  ASSERT_EQ(runMetrosync(run + shellQuote(d + "/r1")).code, 0);
  ASSERT_EQ(runMetrosync(run + shellQuote(d + "/r2")).code, 0);
  const std::string traj = slurp(d + "/r1/trajectory.csv");
  EXPECT_GT(traj.size(), 1000u);
  EXPECT_EQ(traj, slurp(d + "/r2/trajectory.csv"));
  EXPECT_EQ(slurp(d + "/r1/envelope.csv"), slurp(d + "/r2/envelope.csv"));

  for (const char* model : {"full", "slow"}) {
    const std::string sweep = std::string("sweep -q --model ") + model +
                              " --vary platform.friction.mu=0:0.01:3 --vary "
                              "metronomes.1.start.angle=-0.785:-0.5:2 --set simulation.duration=" +
                              (std::string(model) == "full" ? "2" : "30");
    const std::string j1 = d + "/" + model + "-j1", j2 = d + "/" + model + "-j2";
    ASSERT_EQ(runMetrosync(sweep + " --jobs 1 --out " + shellQuote(j1)).code, 0) << model;
    ASSERT_EQ(runMetrosync(sweep + " --jobs 2 --out " + shellQuote(j2)).code, 0) << model;
    const std::string regimes = slurp(j1 + "/regimes.csv");
    EXPECT_GT(regimes.size(), 100u) << model;
    EXPECT_EQ(regimes, slurp(j2 + "/regimes.csv")) << model;
  }
}

}  // namespace
