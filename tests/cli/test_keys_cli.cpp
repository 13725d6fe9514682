// One key language for every command (issue 24, docs/keys.md): a wildcard --set runs exactly the
// rig of one --set per index (the files byte for byte), platform names run exactly their indices,
// a bad key is refused with the same words by --set, --vary, --random, --param and --free after
// what the user typed, and `fit --free metronomes.*.X` reaches fit as one group.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/common/run_metrosync.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

namespace fs = std::filesystem;
using testing_support::CommandResult;
using testing_support::runMetrosync;
using testing_support::scratchDir;
using testing_support::shellQuote;
using testing_support::slurp;

const std::string kRigs = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/";

// `run RIG ARGS` into a fresh directory (its path returned); the run must succeed.
std::string runInto(const std::string& name, const std::string& rig, const std::string& args) {
  const std::string out = scratchDir("keys", name);
  const CommandResult r = runMetrosync("run " + shellQuote(rig) + " " + args +
                                       " -q --no-plot --out " + shellQuote(out));
  EXPECT_EQ(r.code, 0) << args << "\n" << r.err;
  return out;
}

// The CSV files of two runs (trajectory, envelope, and events or order) are the same byte for
// byte, and so are summary.json's resolved rigs.
void expectSameRun(const std::string& a, const std::string& b) {
  int files = 0;
  for (const auto& e : fs::directory_iterator(a)) {
    if (e.path().extension() != ".csv") continue;
    const std::string f = e.path().filename().string();
    EXPECT_EQ(slurp(a + "/" + f), slurp(b + "/" + f)) << f;
    ++files;
  }
  EXPECT_GE(files, 3) << a;
  const auto rig = [](const std::string& d) {
    return nlohmann::json::parse(slurp(d + "/summary.json"))["resolved_rig"];
  };
  EXPECT_EQ(rig(a), rig(b));
}

TEST(KeysCli, WildcardSetRunsEveryIndexSet) {
  const std::string rig = kRigs + "experiment.yaml";
  const std::string every = runInto(
      "every", rig, "--set 'metronomes.*.pendulum.decay_rate=0.3' --set simulation.duration=4");
  const std::string each =
      runInto("each", rig,
              "--set metronomes.0.pendulum.decay_rate=0.3 --set "
              "metronomes.1.pendulum.decay_rate=0.3 --set simulation.duration=4");
  expectSameRun(every, each);
  // the wildcard changed the run
  const std::string plain = runInto("plain", rig, "--set simulation.duration=4");
  EXPECT_NE(slurp(every + "/trajectory.csv"), slurp(plain + "/trajectory.csv"));
}

TEST(KeysCli, PlatformNamesRunTheirIndices) {
  const std::string rig = kRigs + "two-boards-rollers.yaml";
  const std::string dur = " --set simulation.duration=3";
  expectSameRun(runInto("named", rig, "--set platforms.right.friction.mu=0.002" + dur),
                runInto("indexed", rig, "--set platforms.1.friction.mu=0.002" + dur));
  // metronomes.* on a network: every metronome of every platform
  expectSameRun(runInto("all", rig, "--set 'metronomes.*.start.rate=0.1'" + dur),
                runInto("nested", rig, "--set 'platforms.*.metronomes.*.start.rate=0.1'" + dur));
}

// A sweep over a wildcard key: its points are the rigs of one --set per index (sweep-point re-runs
// one of them byte for byte as `run` does with the indices set).
TEST(KeysCli, WildcardSweepPointIsTheRigWithEveryIndexSet) {
  const std::string d = scratchDir("keys", "sweep", true);
  const std::string rig = testing_support::writePairRig(d, 20);
  const CommandResult s =
      runMetrosync("sweep " + shellQuote(rig) +
                   " --vary 'metronomes.*.nu=0.6,0.7' -q --no-plot --out " + shellQuote(d + "/sw"));
  ASSERT_EQ(s.code, 0) << s.err;
  const CommandResult p = runMetrosync("sweep-point " + shellQuote(d + "/sw") +
                                       " 1 -q --no-plot --out " + shellQuote(d + "/pt"));
  ASSERT_EQ(p.code, 0) << p.err;
  const std::string run =
      runInto("sweep-run", rig, "--model slow --set metronomes.0.nu=0.7 --set metronomes.1.nu=0.7");
  EXPECT_EQ(slurp(d + "/pt/envelope.csv"), slurp(run + "/envelope.csv"));
}

// The same bad key from every option: exit 2, nothing written, "RIG: <what was typed>: <why>",
// the why the same for all.
TEST(KeysCli, ABadKeyGetsTheSameWordsFromEveryOption) {
  const std::string rig = kRigs + "experiment.yaml";
  const std::string d = scratchDir("keys", "bad", true);
  const std::string data = d + "/data.csv";
  std::ofstream(data) << "t,theta_1\n0,0.5\n0.01,0.49\n0.02,0.47\n";
  for (const std::string key :
       {"metronomes.*.pendulum.dampnig", "metronomes.2.box_mass", "platform.*.mu"}) {
    struct Case {
      std::string command, typed;
    };
    const std::vector<Case> cases = {
        {"run " + shellQuote(rig), "--set " + key + "=1"},
        {"sweep " + shellQuote(rig), "--vary " + key + "=0:1:2"},
        {"basin " + shellQuote(rig) + " --samples 2", "--random " + key + "=0:1"},
        {"continue " + shellQuote(rig) + " --to 1", "--param " + key},
        {"fit " + shellQuote(rig) + " " + shellQuote(data), "--free " + key}};
    std::string why;
    for (const Case& c : cases) {
      const std::string out = d + "/out";
      const std::string opt = c.typed.substr(0, c.typed.find(' '));
      const CommandResult r =
          runMetrosync(c.command + " " + opt + " " + shellQuote(c.typed.substr(opt.size() + 1)) +
                       " -q --out " + shellQuote(out));
      EXPECT_EQ(r.code, 2) << c.typed << "\n" << r.err;
      EXPECT_FALSE(fs::exists(out)) << c.typed;
      const std::string head = "metrosync: error: " + rig + ": " + c.typed + ": ";
      ASSERT_EQ(r.err.rfind(head, 0), 0u) << r.err << "expected: " << head;
      EXPECT_EQ(r.err.find("--set", head.size()), std::string::npos) << r.err;
      const std::string tail = r.err.substr(head.size());
      if (why.empty()) why = tail;
      EXPECT_EQ(tail, why) << c.typed;
      EXPECT_EQ(tail.rfind(key.substr(0, key.find('.', key.find('.') + 1)), 0), 0u) << tail;
    }
  }
}

// A value a wildcard --set gets wrong is quoted as typed; two options setting one rig key are
// refused, whichever way each spells it.
TEST(KeysCli, MessagesQuoteWhatWasTyped) {
  const std::string rig = kRigs + "experiment-scaled.yaml";
  const std::string out = scratchDir("keys", "quote");
  const CommandResult r =
      runMetrosync("run " + shellQuote(rig) + " --set 'metronomes.*.nu=abc' --out " + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "metrosync: error: " + rig +
                       ": --set metronomes.*.nu=abc: metronomes.0.nu = abc: must be a number\n");
  const std::string net = kRigs + "two-boards-rollers.yaml";
  const CommandResult two = runMetrosync(
      "sweep " + shellQuote(net) +
      " --vary platforms.left.friction.mu=0.001,0.01 --vary platforms.0.friction.mu=0.1,0.2"
      " -q --out " +
      out);
  EXPECT_EQ(two.code, 2);
  EXPECT_NE(two.err.find("--vary platforms.left.friction.mu=0.001,0.01 and --vary "
                         "platforms.0.friction.mu=0.1,0.2: both set platforms.0.friction.mu"),
            std::string::npos)
      << two.err;
  EXPECT_FALSE(fs::exists(out));
}

// A single rig is a network of one platform named "platform" (issue 38, docs/keys.md): README's
// form `platforms.NAME.friction.mu` runs it as its own key does, the files byte for byte; a name
// it does not have is refused by every option (exit 2, nothing written) naming the one it has.
TEST(KeysCli, SingleRigAnswersItsPlatformByNameAndIndex) {
  const std::string rig = kRigs + "experiment.yaml";
  const std::string dur = " --set simulation.duration=3";
  const std::string own = runInto("own", rig, "--set platform.friction.mu=0.01" + dur);
  expectSameRun(runInto("byname", rig, "--set platforms.platform.friction.mu=0.01" + dur), own);
  expectSameRun(runInto("byindex", rig, "--set platforms.0.friction.mu=0.01" + dur), own);
  EXPECT_NE(slurp(own + "/trajectory.csv"),
            slurp(runInto("plain", rig, dur) + "/trajectory.csv"));  // the key did change it

  const std::string d = scratchDir("keys", "single-bad", true);
  const std::string key = "platforms.left.friction.mu";
  const std::vector<std::string> cases = {
      "run " + shellQuote(rig) + " --set " + key + "=0.01",
      "sweep " + shellQuote(rig) + " --vary " + key + "=0:0.01:2",
      "basin " + shellQuote(rig) + " --samples 2 --random " + key + "=0:0.01",
      "continue " + shellQuote(rig) + " --to 0.01 --param " + key,
      "continue " + shellQuote(rig) + " --from 0.001 --to 0.01 --param " + key};
  for (const std::string& c : cases) {
    const CommandResult r = runMetrosync(c + " -q --out " + shellQuote(d + "/out"));
    EXPECT_EQ(r.code, 2) << c << "\n" << r.err;
    EXPECT_NE(r.err.find("platforms.left: no entry of platforms is named 'left' (names: platform;"),
              std::string::npos)
        << c << "\n"
        << r.err;
    EXPECT_EQ(r.err.find("_M_range_check"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(d + "/out")) << c;
  }
}

// The other options take a single rig's platform keys too: a continuation in
// platforms.0.friction.mu is the one in platform.friction.mu (its branches byte for byte), and a
// basin drawing platforms.platform.friction.mu is the one drawing platform.friction.mu (their rows
// byte for byte; the header names the key as typed).
TEST(KeysCli, SingleRigPlatformKeysInContinueAndBasin) {
  const std::string rig = kRigs + "experiment-scaled.yaml";
  const std::string d = scratchDir("keys", "single-options", true);
  std::vector<std::string> branches, basins;
  for (const std::string key : {"platform.friction.mu", "platforms.0.friction.mu"}) {
    const std::string c = d + "/c-" + key;
    const CommandResult r = runMetrosync("continue " + shellQuote(rig) + " --param " + key +
                                         " --from 0.1 --to 0.2 --max-points 5 --no-cycles -q "
                                         "--out " +
                                         shellQuote(c));
    ASSERT_EQ(r.code, 0) << key << "\n" << r.err;
    branches.push_back(slurp(c + "/branches.csv"));
  }
  for (const std::string key : {"platform.friction.mu", "platforms.platform.friction.mu"}) {
    const std::string b = d + "/b-" + key;
    const CommandResult r = runMetrosync("basin " + shellQuote(rig) +
                                         " --samples 2 --jobs 1 --set simulation.tau=20 "
                                         "--random " +
                                         key + "=0.1:0.3 -q --out " + shellQuote(b));
    ASSERT_EQ(r.code, 0) << key << "\n" << r.err;
    basins.push_back(slurp(b + "/basin.csv"));
  }
  // the rows byte for byte (the header names the key as typed)
  const auto body = [](const std::string& csv) { return csv.substr(csv.find('\n')); };
  EXPECT_GT(std::count(branches[0].begin(), branches[0].end(), '\n'), 3);
  EXPECT_EQ(body(branches[0]), body(branches[1]));
  EXPECT_GT(std::count(basins[0].begin(), basins[0].end(), '\n'), 2);
  EXPECT_EQ(body(basins[0]), body(basins[1]));
}

// `fit --free metronomes.*.X` reaches fit as one group of every metronome's X, fitted as one shared
// value (issue 27): fit.json names it as typed and lists the rig keys behind it, and fitted.yaml
// gives every metronome the one value.
TEST(KeysCli, FreeWildcardReachesFitAsOneGroup) {
  const std::string rig = kRigs + "experiment.yaml";
  const std::string d = scratchDir("keys", "fit", true);
  const std::string data = d + "/data.csv";
  std::ofstream(data) << "t,theta_1\n0,0.785\n0.01,0.77\n0.02,0.72\n0.03,0.65\n";
  const CommandResult r = runMetrosync("fit " + shellQuote(rig) + " " + shellQuote(data) +
                                       " --free 'metronomes.*.pendulum.decay_rate' --no-plot -q "
                                       "--out " +
                                       shellQuote(d + "/o"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(d + "/o/fit.json"));
  EXPECT_EQ(j["free"], nlohmann::json({"metronomes.*.pendulum.decay_rate"}));
  EXPECT_EQ(
      j["keys"]["metronomes.*.pendulum.decay_rate"],
      nlohmann::json({"metronomes.0.pendulum.decay_rate", "metronomes.1.pendulum.decay_rate"}));
  const Rig fitted = loadRigFile(d + "/o/fitted.yaml");
  EXPECT_EQ(fitted.metronomes[0].damping_kg_s, fitted.metronomes[1].damping_kg_s);
}

}  // namespace
}  // namespace metrosync
