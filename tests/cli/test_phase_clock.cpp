// METROSYNC_PHASES=1 (tools/cli/phase_clock.h): `metrosync run` says where its time goes, one
// line per phase in the order the run goes through them; the phases follow each other without a
// gap, the run's phase holds the engine's wall_seconds, and without the variable nothing is said.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/common/run_metrosync.h"

namespace {

namespace ts = metrosync::testing_support;

struct Phase {
  std::string name;
  double ms = 0, at = 0;
};

// The phase lines of a run's stderr; the first, "main", with ms = 0.
std::vector<Phase> phases(const std::string& err) {
  std::vector<Phase> v;
  std::istringstream in(err);
  for (std::string line; std::getline(in, line);) {
    Phase p;
    char name[64] = {};
    if (std::sscanf(line.c_str(), "metrosync: phase main at %lf s", &p.at) == 1)
      p.name = "main";
    else if (std::sscanf(line.c_str(), "metrosync: phase %63s %lf ms (at %lf s)", name, &p.ms,
                         &p.at) == 3)
      p.name = name;
    else
      continue;
    v.push_back(p);
  }
  return v;
}

const std::string kRig = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/bench/peer-n2.yaml";

}  // namespace

TEST(PhaseClock, RunSaysWhereItsTimeGoes) {
  const std::string out = ts::scratchDir("phases", "run");
  const auto r = ts::runMetrosync(
      "run " + ts::shellQuote(kRig) + " --quiet --no-plot --out " + ts::shellQuote(out),
      {"", "METROSYNC_PHASES=1"});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::vector<Phase> p = phases(r.err);
  std::vector<std::string> names;
  for (const Phase& x : p) names.push_back(x.name);
  EXPECT_EQ(names, (std::vector<std::string>{"main", "args", "rig", "folder", "run", "files",
                                             "summary", "sync", "print"}))
      << r.err;
  for (size_t k = 1; k < p.size(); ++k) {
    EXPECT_GE(p[k].ms, 0.0) << p[k].name;
    // each phase ends where the next begins: its length is the gap between the two readings
    EXPECT_NEAR(p[k].ms, 1e3 * (p[k].at - p[k - 1].at), 2e-3) << p[k].name;
  }
  const nlohmann::json s = nlohmann::json::parse(ts::slurp(out + "/summary.json"));
  const double wall_ms = 1e3 * s.at("wall_seconds").get<double>();
  EXPECT_GE(p[4].ms, wall_ms) << "the run's phase holds the engine's own timing";
  std::filesystem::remove_all(out);
}

TEST(PhaseClock, NothingIsSaidWithoutTheVariable) {
  const std::string out = ts::scratchDir("phases", "quiet");
  for (const char* env : {"", "METROSYNC_PHASES=0", "METROSYNC_PHASES="}) {
    const auto r = ts::runMetrosync(
        "run " + ts::shellQuote(kRig) + " --quiet --no-plot --out " + ts::shellQuote(out),
        {"", env});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err, "") << env;
  }
  std::filesystem::remove_all(out);
}
