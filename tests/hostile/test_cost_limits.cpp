// Issue 29: one cost estimate before any work, for every command: the run's length in fast
// periods (sweep, basin, continue, fit and animate too, not only run's output), a network's
// platforms, stack depth and metronomes over all its platforms, a fit's data file and record.
// Each limit at its boundary; the commands end to end under run_limited.sh (200 MB, 5 s).
#include <cmath>
#include <fstream>

#include "tests/hostile/hostile_support.h"
#include "yaml/network_loader.h"

namespace metrosync::hostile {
namespace {

using testing_support::scratchDir;

// experiment-map.yaml with tau set so that the run spans `periods` fast periods
// (periods = tau / (2 pi epsilon) in a scaled rig).
std::string mapRigOfPeriods(double periods) {
  const double tau = periods * 2.0 * M_PI * 0.07319;
  char buf[64];
  std::snprintf(buf, sizeof buf, "simulation.tau=%.17g", tau);
  return buf;
}

TEST(CostLimits, RunLengthInPeriodsAtItsBoundary) {
  const std::string map = shippedRig("experiment-map.yaml");
  EXPECT_EQ(loadError(map, {mapRigOfPeriods(kMaxRunPeriods * 0.999)}), "");
  const std::string msg = loadError(map, {mapRigOfPeriods(kMaxRunPeriods * 1.001)});
  EXPECT_NE(msg.find("fast periods"), std::string::npos) << msg;
  EXPECT_NE(msg.find("above the limit of 1e+08 for any command"), std::string::npos) << msg;
  EXPECT_EQ(msg.rfind("rig.yaml: --set simulation.tau=", 0), 0u) << msg;
}

// A network of `platforms` boards of `per` metronomes each, board k resting on board k - 1 for
// the first `stacked` boards.
std::string networkText(int platforms, int per, int stacked, bool locked = false) {
  std::string t = "units: physical\nname: net\nplatforms:\n";
  for (int k = 0; k < platforms; ++k) {
    t += "  - name: p" + std::to_string(k) + "\n    mass: 0.14\n";
    t += "    friction: {law: coulomb, mu: 6.5e-4}\n";
    if (k > 0 && k < stacked) t += "    on: p" + std::to_string(k - 1) + "\n";
    t += "    metronomes:\n";
    for (int m = 0; m < per; ++m)
      t += std::string("      - {box_mass: 0.06, pendulum: {mass: 0.02, length: 0.02, damping: ") +
           "0.01}, escapement: {angle: 0.24, impulse: 1e-5}, start: {angle: 0.5}" +
           (locked ? ", locked: true" : "") + "}\n";
  }
  return t + "simulation:\n  duration: 1\n";
}

std::string networkError(const std::string& text) {
  try {
    loadNetworkText(text, "net.yaml", {});
  } catch (const RigError& e) {
    return e.what();
  }
  return "";
}

TEST(CostLimits, NetworkPlatformsStackAndMetronomesAtTheirBoundaries) {
  EXPECT_EQ(networkError(networkText(kMaxStackDepth, 1, kMaxStackDepth)), "");
  std::string msg = networkError(networkText(kMaxStackDepth + 1, 1, kMaxStackDepth + 1));
  EXPECT_NE(msg.find(".on: a stack of 9 platforms, one on another (at most 8"), std::string::npos)
      << msg;
  EXPECT_TRUE(located(msg, "net.yaml")) << msg;
  EXPECT_EQ(networkError(networkText(static_cast<int>(kMaxPlatforms), 1, 0)), "");
  msg = networkError(networkText(static_cast<int>(kMaxPlatforms) + 1, 1, 0));
  EXPECT_NE(msg.find("platforms: 65 platforms (at most 64"), std::string::npos) << msg;
  // 1000 metronomes over two platforms load; 1002 do not (main: accepted)
  EXPECT_EQ(networkError(networkText(2, 500, 0)), "");
  msg = networkError(networkText(2, 501, 0));
  EXPECT_NE(msg.find("platforms.1: brings the network to 1002 metronomes (at most 1000"),
            std::string::npos)
      << msg;
  // every metronome locked: refused where the platforms are (main: exit 1, no file, no key)
  msg = networkError(networkText(2, 2, 0, true));
  EXPECT_NE(msg.find("platforms.1.metronomes.1.locked = true: every metronome of the network is "
                     "locked"),
            std::string::npos)
      << msg;
  EXPECT_TRUE(located(msg, "net.yaml")) << msg;
}

// The commands end to end: refused in well under the 5 s of runLimited, nothing written.
TEST(CostLimits, EveryCommandRefusesAnEndlessRunBeforeAnyWork) {
  const std::string d = scratchDir("cost", "commands", true);
  const std::string stack = d + "/stack.yaml", locked = d + "/locked.yaml";
  std::ofstream(stack) << networkText(1000, 1, 1000);  // 1000 stacked platforms (main: 67 s)
  std::ofstream(locked) << networkText(2, 2, 0, true);
  const std::vector<std::string> cases = {
      "run --engine direct " + shellQuote(stack),
      "sweep --vary couplings.0.k=1:2:2 " + shellQuote(stack),
      "run --engine direct " + shellQuote(locked),
      "sweep --vary platforms.0.mass=0.1:0.2:2 " + shellQuote(locked),
  };
  for (const std::string& args : cases) {
    const std::string out = d + "/out";
    const CommandResult r = runLimited(args, out);
    expectRefusedCleanly(r, out, args);
  }
}

// fit's data: a stray row at t = 1e9 s, and a 200 MB line, refused before any model run.
TEST(CostLimits, FitDataRecordAndLineLengths) {
  const std::string d = scratchDir("cost", "fit", true);
  const std::string stray = d + "/stray.csv", wide = d + "/wide.csv";
  {
    std::ofstream f(stray);
    f << "t,theta_1\n";
    for (int k = 0; k < 50; ++k) f << k * 0.01 << "," << 0.5 * std::cos(k * 0.1) << "\n";
    f << "1e9,0.1\n";
  }
  {
    std::ofstream f(wide);
    f << "t,theta_1\n0," << std::string(1 << 20, '1') << "\n";
  }
  const std::string rig = shellQuote(sourceDir() + "/yaml/rigs/experiment.yaml");
  CommandResult r = runLimited(
      "fit " + rig + " " + shellQuote(stray) + " --free metronomes.0.pendulum.decay_rate",
      d + "/out");
  expectRefusedCleanly(r, d + "/out", "stray");
  EXPECT_NE(r.err.find(stray + ":52: the record runs from t = 0 to 1e+09 s"), std::string::npos)
      << r.err;
  r = runLimited("fit " + rig + " " + shellQuote(wide) + " --free metronomes.0.pendulum.decay_rate",
                 d + "/out");
  expectRefusedCleanly(r, d + "/out", "wide");
  EXPECT_NE(r.err.find(wide + ":2: a line of"), std::string::npos) << r.err;
}

// The duplicate-key check is linear: 24 000 keys of 63 characters sharing a 58-character prefix
// in one map (the node budget allows about 25 000) are refused in 0.5 s (main scanned the map
// for every key: 4.4 s on the 2-core machine, measured with /usr/bin/time). The 2 s limit keeps a
// factor 4 in hand for a loaded machine.
TEST(CostLimits, ManyKeysInOneMapAreCheckedInLinearTime) {
  const std::string d = scratchDir("cost", "keys", true);
  const std::string rig = d + "/keys.yaml";
  {
    std::ofstream f(rig);
    f << "units: physical\nplatform:\n";
    char key[80];
    for (int k = 0; k < 24000; ++k) {
      std::snprintf(key, sizeof key, "%s%05d", std::string(58, 'x').c_str(), k);
      f << "  " << key << ": 1\n";
    }
  }
  testing_support::RunIn in;
  in.env = "timeout -s KILL 2";
  const CommandResult r =
      runMetrosync("run " + shellQuote(rig) + " --out " + shellQuote(d + "/o"), in);
  EXPECT_EQ(r.code, 2) << r.err;  // 137: killed at 2 s
  EXPECT_NE(r.err.find("unknown key"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace metrosync::hostile
