// Issue 39: every message located -- the file, line and column or the option, the key and the
// value -- and numbers in messages as the user gave them or saturated, never overflowed. The
// issue's cases and probes of our own of each class; each comment says what main did.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/hostile/hostile_support.h"

namespace metrosync::hostile {
namespace {

namespace fs = std::filesystem;
using testing_support::scratchDir;

struct Case {
  std::string args, says;
};

// Each case refused with exit 2, nothing written, its message holding `says`.
void expectMessages(const std::vector<Case>& cases) {
  for (const Case& c : cases) {
    // animate's --out is the video file
    const std::string out =
        scratchDir("located", "case", false) + (c.args.rfind("animate", 0) == 0 ? ".mp4" : "");
    const CommandResult r = runLimited(c.args, out);
    expectRefusedCleanly(r, out, c.args);
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
  }
}

// main: "-9223372036854775808 frames" (the count overflowed a long before it was checked)
TEST(LocatedMessages, AnimateSaysItsFrameCountAsANumberNeverOverflowed) {
  expectMessages({
      {"animate --speed 1e-300 --to 100",
       "--fps 30 x (100 - 0) / --speed 1e-300 = 3e+303 frames: must be 1 to 108000"},
      {"animate --to 1e300", "--fps 30 x (1e+300 - 0) / --speed 1 = 3e+301 frames"},
      {"animate --to 1e308 --speed 1e-308", "= more than 1.79769e+308 frames"},
      // ours: --from so far out that its frame's index passes what a long counts exactly
      {"animate --from 1e17 --to 100000000000000016",
       "--from 1e+17 at --fps 30 / --speed 1 is frame 3e+18 of the video's time line"},
  });
}

// The network files of these cases, written into `dir`.
void writeNetworks(const std::string& dir) {
  const std::string metronome =
      "{box_mass: 0.1, pendulum: {mass: 0.02, length: 0.05, inertia: 1.16e-4, decay_rate: 0.3}, "
      "escapement: {angle: 0.2, steady_amplitude: 0.5}, start: {angle: 0.1}";
  const std::string head =
      "units: physical\nname: n\nplatforms:\n"
      "  - name: left\n    mass: 1.0\n    friction: {law: viscous, c: 0.05}\n"
      "    metronomes:\n      - " +
      metronome;
  const std::string right =
      "  - name: right\n    mass: 1.0\n    friction: {law: coulomb, mu: 0.01}\n";
  const std::string tail =
      "couplings:\n  - {between: [left, right], k: 5.0}\nsimulation: {duration: 1}\n";
  std::ofstream(dir + "/bare.yaml") << head << "}\n" << right << tail;
  std::ofstream(dir + "/two.yaml") << head << "}\n"
                                   << right << "    metronomes:\n      - " << metronome << "}\n"
                                   << tail;
  std::ofstream(dir + "/locked.yaml")
      << head << ", locked: true}\n"
      << right << "    metronomes:\n      - " << metronome << ", locked: true}\n"
      << tail;
}

TEST(LocatedMessages, ANetworkSaysWhichPlatformAndWhichKey) {
  const std::string d = scratchDir("located", "networks", true);
  writeNetworks(d);
  const auto f = [&](const std::string& name) { return shellQuote(d + "/" + name); };
  expectMessages({
      // main: "bare.yaml:9:5: metronomes: missing" (which platform's?)
      {"run " + f("bare.yaml"), "bare.yaml:9:5: platforms.1.metronomes: missing"},
      // ours: the same by a --set; main: "metronomes = (a list): must hold at least one"
      {"run " + f("two.yaml") + " --set 'platforms.right.metronomes=[]'",
       "two.yaml: --set platforms.right.metronomes=[]: platforms.1.metronomes = (a list): must "
       "hold at least one metronome"},
      // main: blamed the file's `platforms:` line, not the --set that locked them
      {"run " + f("two.yaml") + " --set 'metronomes.*.locked=true'",
       "two.yaml: --set metronomes.*.locked=true: platforms.1.metronomes.0.locked = true: every "
       "metronome of the network is locked"},
      // ours: locked in the file: the last one's line, key and value
      {"run " + f("locked.yaml"), "locked.yaml:13:"},
      {"run " + f("locked.yaml"), ": platforms.1.metronomes.0.locked = true: every metronome"},
  });
}

// Ours, found by the fuzz target `keys` (tools/fuzz): a platform's name on a rig without
// platforms. main: exit 1, "vector::_M_range_check: __n (which is 0) >= this->size() (which is 0)"
// A single rig is the network of one platform named `platform` (issue 38): another name is
// refused naming the one it has, before any file is written.
TEST(LocatedMessages, APlatformNameOnASinglePlatformRigIsAKeyError) {
  expectMessages({
      {"run --set platforms.right.friction.mu=0.02",
       "<default rig>: --set platforms.right.friction.mu=0.02: platforms.right: no entry of "
       "platforms is named 'right' (names: platform; this rig has one platform)"},
      {"sweep --vary platforms.right.friction.mu=0:1:2",
       "<default rig>: --vary platforms.right.friction.mu=0:1:2: platforms.right: no entry of "
       "platforms is named 'right' (names: platform; this rig has one platform)"},
  });
}

TEST(LocatedMessages, ContinueSaysItsKeyValueAndStart) {
  const std::string map = rigPath("experiment-map.yaml");
  expectMessages({
      // main: "Newton does not converge ... (--start 1,inf,0)": inf taken as a start
      {"continue " + map + " --param metronomes.1.alpha --to 1 --start 1,inf,0",
       "--start 1,inf,0: 'inf' is not a finite number"},
      // main: "--start: A_1 must be >= 0" (neither the value nor what was typed)
      {"continue " + map + " --param metronomes.1.alpha --to 1 --start nan,1,0",
       "--start nan,1,0: 'nan' is not a finite number"},
      {"continue " + map + " --param metronomes.1.alpha --to 1 --start -1,1,0",
       "--start -1,1,0: A_1 = -1: must be >= 0"},
      // main: "the rig's start does not settle ..." without the key or its value
      {"continue --param metronomes.1.pendulum.decay_rate --to 1 --from 18446744073709551617",
       "--param metronomes.1.pendulum.decay_rate = 1.8446744073709552e+19: the rig's start does "
       "not settle"},
      // ours: main said "--param metronomes.*.alpha: the key is not set" without the rig
      {"continue " + map + " --param 'metronomes.*.alpha' --to 1",
       "experiment-map.yaml: --param metronomes.*.alpha: the key is not set in the rig"},
      // the issue's --param index past 2^64 (located on main too: a guard that stays)
      {"continue " + map + " --param metronomes.18446744073709551617.alpha --to 1",
       "experiment-map.yaml: --param metronomes.18446744073709551617.alpha: "
       "metronomes.18446744073709551617: an index of more than 8 digits"},
  });
}

TEST(LocatedMessages, ADataFileSaysItsLine) {
  const std::string d = scratchDir("located", "data", true);
  {  // 70 MB of empty lines: over the 64 MiB limit at line 2^26 + 1
    std::ofstream big(d + "/big.csv", std::ios::binary);
    const std::string mb(1 << 20, '\n');
    for (int k = 0; k < 70; ++k) big << mb;
  }
  std::ofstream(d + "/empty-column.csv")
      << "# a record\nt,theta_1,theta_2\n0,0.1,\n0.1,0.2,\n0.2,0.3,\n";
  const std::string rig = rigPath("experiment.yaml");
  expectMessages({
      // main: "big.csv: larger than 64 MiB" (no line, no size)
      {"fit " + rig + " " + shellQuote(d + "/big.csv") + " --free platform.friction.mu",
       "big.csv:67108865: the file passes 67108864 bytes (64 MiB) on this line; it has 73400320"},
      {"measure --decay " + shellQuote(d + "/big.csv"), "big.csv:67108865: the file passes"},
      // ours: main said "empty-column.csv: column theta_2 has no values" (no line)
      {"fit " + rig + " " + shellQuote(d + "/empty-column.csv") + " --free platform.friction.mu",
       "empty-column.csv:2: column theta_2 has no values"},
  });
  fs::remove(d + "/big.csv");
}

}  // namespace
}  // namespace metrosync::hostile
