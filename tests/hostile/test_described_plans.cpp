// Issue 39: a sweep's plan is described, not materialized. A grid of 10^12 points (its cap lifted
// with --force) starts in bounded memory and writes a sweep.json of a few kB: on main its two
// axes of 10^6 values were listed as texts in memory and in sweep.json (about 650 MB and 59 MB
// before any point ran). With --resume, the two bits a point it needs are stated and refused up
// front past the limit (main: a vector of 2.5 * 10^11 bytes asked for, then bad_alloc).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "sim/analysis/sweep.h"
#include "tests/common/sweep_axis_values.h"
#include "tests/hostile/hostile_support.h"

namespace metrosync::hostile {
namespace {

namespace fs = std::filesystem;
using testing_support::scratchDir;
using testing_support::slurp;

const std::string kHugeGrid =
    " --vary platform.friction.mu=0.01:0.3:1000000 --vary metronomes.0.start.phi=0:2pi:1000000:open"
    " --force";

// Under run_limited.sh (200 MB of address space), stopped by SIGINT after 10 s: points ran, the
// sweep ended as an interrupted one, sweep.json small and describing the grid.
TEST(DescribedPlans, ATrillionPointSweepStartsInBoundedMemory) {
  const std::string out = scratchDir("plans", "trillion");
  testing_support::RunIn in;
  in.env = "RUN_LIMITED_SECONDS=30 " + shellQuote(sourceDir() + "/tests/hostile/run_limited.sh") +
           " timeout --foreground --preserve-status -s INT 10";
  const CommandResult r = runMetrosync(
      "sweep " + shellQuote(sourceDir() + "/yaml/rigs/experiment-scaled.yaml") +
          " --model slow --jobs 2 -q --no-plot" + kHugeGrid + " --out " + shellQuote(out),
      in);
  EXPECT_EQ(r.code, 3) << r.err;  // interrupted: not out of memory (1), not killed (137)
  ASSERT_TRUE(fs::exists(out + "/sweep.json")) << r.err;
  const std::string text = slurp(out + "/sweep.json");
  EXPECT_LT(text.size(), 16000u) << "sweep.json lists the grid";
  const nlohmann::json status = nlohmann::json::parse(text);
  EXPECT_EQ(status["points"]["grid"].get<long>(), 1000000000000L);
  EXPECT_GE(status["points"]["done"].get<long>(), 1) << "no point finished within 10 s";
  const nlohmann::json& axis = status["grid"]["axes"][1];
  EXPECT_FALSE(axis.contains("values"));  // described by its spec
  EXPECT_EQ(axis["spec"], "0:2pi:1000000:open");
  // the description is the grid: read back, it gives every value the sweep ran
  const SweepGrid back = SweepGrid::fromJson(status["grid"]);
  const SweepAxis first = parseVary("platform.friction.mu=0.01:0.3:1000000");
  for (long k : {0L, 1L, 499999L, 999999L}) EXPECT_EQ(back.axes()[0].text(k), first.text(k)) << k;
  EXPECT_EQ(back.axes()[0].text(999999), "0.3");
}

TEST(DescribedPlans, ResumeStatesTheMemoryItNeedsAndRefusesPastTheLimit) {
  const std::string out = scratchDir("plans", "resume", false);
  const CommandResult r =
      runLimited("sweep " + shellQuote(sourceDir() + "/yaml/rigs/experiment-scaled.yaml") +
                     " --model slow -q --no-plot --resume" + kHugeGrid,
                 out);
  expectRefusedCleanly(r, out, "resume");
  EXPECT_NE(r.err.find("--resume: the grid's 1000000000000 points need about 2.5e+11 bytes of "
                       "memory to know which are done (two bits a point), above the limit of "),
            std::string::npos)
      << r.err;
  // at the default cap (10^7 points) --resume is let through: 2.5 MB
  const std::string ok = scratchDir("plans", "resume-ok", false);
  const CommandResult small =
      runLimited("sweep " + shellQuote(sourceDir() + "/yaml/rigs/experiment-map.yaml") +
                     " -q --no-plot --resume --set simulation.tau=1"
                     " --vary platform.friction.mu=0.01:0.3:2",
                 ok);
  EXPECT_EQ(small.code, 0) << small.err;
}

// A range axis's values are computed when asked for, the same numbers the listed form had: both
// ends exact, every text read back to its value, the open form leaving TO out.
TEST(DescribedPlans, AnAxisComputesEachValueAsItWasListed) {
  const SweepAxis a = parseVary("x=0.01:0.3:1000000");
  EXPECT_TRUE(a.listed.empty());
  EXPECT_EQ(a.text(0), "0.01");
  EXPECT_EQ(a.text(999999), "0.3");
  EXPECT_EQ(a.value(500000), std::strtod(a.text(500000).c_str(), nullptr));
  EXPECT_NEAR(a.value(500000), 0.01 + 0.29 * 500000.0 / 999999.0, 1e-15);
  const SweepAxis list = parseVary("x=0.4,0.2,pi");
  EXPECT_EQ(testing_support::axisTexts(list),
            (std::vector<std::string>{"0.4", "0.2", "3.14159265358979"}));
  // sweep.json lists at most kMaxListedAxisValues values per axis
  const SweepGrid grid({parseVary("a=0:1:1000"), parseVary("b=0:1:1001")});
  const nlohmann::json j = grid.toJson();
  EXPECT_EQ(j["axes"][0]["values"].size(), 1000u);
  EXPECT_FALSE(j["axes"][1].contains("values"));
  EXPECT_TRUE(SweepGrid::fromJson(j).axes()[1].sameValues(grid.axes()[1]));
  // listed values that are not the spec's: not this grid
  nlohmann::json other = j;
  other["axes"][0]["values"][3] = "0.5";
  EXPECT_THROW(SweepGrid::fromJson(other), SweepInputError);
}

}  // namespace
}  // namespace metrosync::hostile
