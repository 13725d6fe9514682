// Issue 29, the remaining refusals and messages: basin's overlapping --random pair, sweep-point's
// half-written folder, a damaged member of envelopes.csv.gz on --resume, continue's messages for
// a --to beyond the numbers' range and a mistyped --param, and raw terminal escapes from a fit
// data file. Each failed on main (the comments say how).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/hostile/hostile_support.h"
#include "tools/report/envelope_store.h"

namespace metrosync::hostile {
namespace {

namespace fs = std::filesystem;
using testing_support::scratchDir;
using testing_support::slurp;

// main: accepted, the wildcard and metronome 0 drawn as two columns of one key
TEST(SecondPass, BasinRefusesAWildcardAndAConcreteRandomOfOneKey) {
  const std::string out = scratchDir("second", "basin", false);
  const CommandResult r =
      runLimited("basin " + rigPath("experiment-map.yaml") +
                     " --samples 2 --random 'metronomes.*.start.A=1:2' --random "
                     "metronomes.0.start.A=1:2",
                 out);
  expectRefusedCleanly(r, out, "overlap");
  EXPECT_NE(r.err.find("--random metronomes.*.start.A=1:2 and --random metronomes.0.start.A=1:2: "
                       "both set metronomes.0.start.A"),
            std::string::npos)
      << r.err;  // the words of the key resolver (docs/keys.md)
}

// main: exit 2 but point-0/ made, with sweep-rig.yaml in it
TEST(SecondPass, SweepPointWithAnInvalidStoredRigWritesNothing) {
  const std::string d = scratchDir("second", "point", true);
  ASSERT_EQ(runLimited("sweep " + rigPath("experiment-map.yaml") +
                           " --vary platform.friction.mu=0.01:0.1:2 -q --no-plot",
                       d + "/s")
                .code,
            0);
  nlohmann::json j = nlohmann::json::parse(slurp(d + "/s/sweep.json"));
  std::string text = j["rig"]["text"];
  text.replace(text.find("nu: 0.6544"), 10, "nu: -0.65");
  j["rig"]["text"] = text;
  std::ofstream(d + "/s/sweep.json") << j.dump(2);
  testing_support::RunIn in;
  in.env = shellQuote(sourceDir() + "/tests/hostile/run_limited.sh");
  const CommandResult r =
      testing_support::runMetrosync("sweep-point " + shellQuote(d + "/s") + " 0", in);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("metronomes.0.nu = -0.65"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(d + "/s/point-0"));
}

// The offsets of the gzip members of a file (each starts 1f 8b 08).
std::vector<size_t> gzipMembers(const std::string& bytes) {
  std::vector<size_t> at;
  for (size_t k = bytes.find("\x1f\x8b\x08"); k != std::string::npos;
       k = bytes.find("\x1f\x8b\x08", k + 1))
    at.push_back(k);
  return at;
}

// main: the damaged member and those after it were cut, but their points were not run again
TEST(SecondPass, ResumeRerunsThePointsOfADamagedEnvelopeMember) {
  const std::string out = scratchDir("second", "gzip", false);
  const std::string args = "sweep " + rigPath("experiment-map.yaml") +
                           " --vary platform.friction.mu=0.01:0.1:6 -q --no-plot --jobs 1 "
                           "--keep envelope --resume";
  ASSERT_EQ(runLimited(args, out).code, 0);
  const std::string store = out + "/envelopes.csv.gz";
  ASSERT_EQ(readEnvelopeStore(store).size(), 6u);
  std::string bytes = slurp(store);
  const std::vector<size_t> members = gzipMembers(bytes);
  ASSERT_GE(members.size(), 5u);  // the header's, then one per point
  const size_t mid = (members[3] + members[4]) / 2;
  bytes[mid] = static_cast<char>(bytes[mid] ^ 0x5A);  // a complete member, damaged inside
  std::ofstream(store, std::ios::binary) << bytes;
  ASSERT_LT(readEnvelopeStore(store).size(), 6u);
  const CommandResult r = runLimited(args, out);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("they run again"), std::string::npos) << r.err;
  EXPECT_EQ(readEnvelopeStore(store).size(), 6u);
  EXPECT_EQ(testing_support::csvRows(out + "/regimes.csv").size(), 7u);
}

TEST(SecondPass, ContinueMessages) {
  const std::string map = rigPath("experiment-map.yaml");
  struct Case {
    std::string args, says;
  };
  const std::vector<Case> cases = {
      // main: exit 1 "slow flow: nu is not finite"
      {"--param platform.friction.mu --to 1e308", "--param platform.friction.mu from 0.0328"},
      // main: "the key is not set in the rig (its default applies)"
      {"--param platform.friction.mux --to 1",
       "--param platform.friction.mux: platform.friction.mux: unknown key (did you mean 'mu'?)"},
  };
  for (const Case& c : cases) {
    const std::string out = scratchDir("second", "continue", false);
    const CommandResult r = runLimited("continue " + map + " " + c.args, out);
    expectRefusedCleanly(r, out, c.args);
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
  }
}

// main: the ESC and BEL of the header reached the terminal as they were
TEST(SecondPass, AFitDataHeaderWithTerminalEscapesIsQuotedEscaped) {
  const std::string d = scratchDir("second", "escape", true);
  std::ofstream(d + "/data.csv") << "t,\x1b]0;pwned\x07theta_1\n0,0.1\n0.1,0.2\n0.2,0.3\n";
  const CommandResult r =
      runLimited("fit " + rigPath("experiment.yaml") + " " + shellQuote(d + "/data.csv") +
                     " --free metronomes.0.pendulum.decay_rate",
                 d + "/out");
  expectRefusedCleanly(r, d + "/out", "escape");
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\x07'), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\\x1B]0;pwned\\x07"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace metrosync::hostile
