// Networks of platforms (docs/networks.md): what loads, and every bad input of issue 13 with its
// file, key and line. Rigs are inline; a bad value replaces one numbered line of a valid rig.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "tests/yaml/same_rig.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

// A valid network; the line numbers in the margin are what the tests below replace.
const char* const kNet = R"(units: physical
name: net
platforms:
  - name: left
    mass: 1.2
    friction: {law: viscous, c: 0.05}
    spring: {k: 80.0, c: 0.1}
    metronomes:
      - {box_mass: 0.06, pendulum: {mass: 0.02, length: 0.02, damping: 0.01}, escapement: {angle: 0.2, impulse: 1e-5}, start: {angle: 0.5}}
  - name: top
    on: left
    mass: 0.3
    friction: {law: coulomb, mu: 0.02}
    metronomes:
      - {box_mass: 0.06, pendulum: {mass: 0.02, length: 0.02, damping: 0.01}, start: {angle: -0.5}}
  - name: right
    mass: 1.0
    friction: {law: none}
    metronomes:
      - {box_mass: 0.06, pendulum: {mass: 0.02, length: 0.03, damping: 0.01}}
      - {box_mass: 0.06, pendulum: {mass: 0.02, length: 0.03, damping: 0.01}}
couplings:
  - {between: [left, right], k: 5.0, c: 0.0}
simulation:
  duration: 10
)";

std::string withLine(const std::string& text, int line, const std::string& with) {
  std::istringstream in(text);
  std::string out, l;
  for (int i = 1; std::getline(in, l); ++i) out += (i == line ? with : l) + "\n";
  return out;
}

// The message of loading `text`, or "" if it loads.
std::string errorOf(const std::string& text) {
  try {
    loadNetworkText(text, "net.yaml");
  } catch (const RigError& e) {
    return e.what();
  }
  return "";
}

TEST(NetworkLoader, ReadsPlatformsStackingAndCouplings) {
  const Network net = loadNetworkText(kNet, "net.yaml");
  ASSERT_EQ(net.platforms.size(), 3u);
  EXPECT_EQ(net.name, "net");
  EXPECT_EQ(net.platforms[0].name, "left");
  EXPECT_EQ(net.platforms[0].rig.platform.friction.name(), std::string("viscous"));
  EXPECT_DOUBLE_EQ(net.platforms[0].rig.platform.spring_N_m, 80.0);
  EXPECT_DOUBLE_EQ(net.platforms[0].spring_c_Ns_m, 0.1);
  EXPECT_EQ(net.platforms[1].on, 0);
  EXPECT_EQ(net.platforms[2].on, -1);
  EXPECT_EQ(net.numMetronomes(), 4);
  EXPECT_EQ(net.firstMetronome(2), 2);
  ASSERT_EQ(net.couplings.size(), 1u);
  EXPECT_EQ(net.couplings[0].a, 0);
  EXPECT_EQ(net.couplings[0].b, 2);
  EXPECT_DOUBLE_EQ(net.couplings[0].k_N_m, 5.0);
  // the lower platform carries the upper one (normal force of its friction)
  EXPECT_DOUBLE_EQ(net.carriedMass(0),
                   net.platforms[0].rig.totalMass() + net.platforms[1].rig.totalMass());
  EXPECT_DOUBLE_EQ(net.carriedMass(1), 0.3 + 0.06 + 0.02);
}

TEST(NetworkLoader, OverridesReachCouplings) {
  const Network net = loadNetworkText(kNet, "net.yaml", {"couplings.0.k=7.5"});
  EXPECT_DOUBLE_EQ(net.couplings[0].k_N_m, 7.5);
}

TEST(NetworkLoader, BadInputNamesFileKeyAndLine) {
  struct Case {
    int line;
    std::string with, expected;
  };
  const Case cases[] = {
      {23, "  - {between: [left, middle], k: 5.0}",
       "net.yaml:23:22: couplings.0.between.1 = middle: no platform has this name"},
      {23, "  - {between: [left, left], k: 5.0}",
       "net.yaml:23:15: couplings.0.between: couples platform left to itself"},
      {16, "  - name: left", "net.yaml:16:11: platforms.2.name = left: duplicate: platforms.0"},
      {23, "  - {between: [left, right], k: -5.0}",
       "net.yaml:23:33: couplings.0.k = -5.0: must be >= 0"},
      {23, "  - {between: [left, right]}", "net.yaml:23:5: couplings.0.k: missing"},
      {11, "    on: nowhere", "net.yaml:11:9: platforms.1.on = nowhere: no platform has this name"},
      {11, "    on: top", "net.yaml:11:9: platforms.1.on = top: a platform cannot rest on itself"},
      {5, "    mass: -1.2", "net.yaml:5:11: platforms.0.mass = -1.2: must be > 0"},
      {9, "      - {box_mass: 0.06, pendulum: {mass: 0, length: 0.02, damping: 0.01}}",
       "net.yaml:9:43: platforms.0.metronomes.0.pendulum.mass = 0: must be > 0"},
      {7, "    spring: {k: -80.0}", "net.yaml:7:17: platforms.0.spring.k = -80.0: must be >= 0"},
      {4, "  - nom: left", "net.yaml:4:5: platforms.0.nom"},
  };
  for (const Case& c : cases) {
    const std::string msg = errorOf(withLine(kNet, c.line, c.with));
    EXPECT_NE(msg.find(c.expected), std::string::npos)
        << "got: " << msg << "\nwanted: " << c.expected;
  }
}

TEST(NetworkLoader, CycleOfOnIsRefused) {
  // left on top (and top on left); left's ground spring removed
  const std::string msg2 = errorOf(withLine(withLine(kNet, 7, "    on: top"), 5, "    mass: 1.2"));
  EXPECT_NE(msg2.find("a cycle of `on`"), std::string::npos) << msg2;
  EXPECT_NE(msg2.find("net.yaml:7:9: platforms.0.on"), std::string::npos) << msg2;
}

TEST(NetworkLoader, AllFixedButCoupledIsRefused) {
  std::string text = withLine(kNet, 6, "    friction: {law: fixed}");
  text = withLine(text, 7, "");
  text = withLine(text, 11, "");
  text = withLine(text, 13, "    friction: {law: fixed}");
  text = withLine(text, 18, "    friction: {law: fixed}");
  const std::string msg = errorOf(text);
  EXPECT_NE(msg.find("net.yaml:23:3: couplings: every platform is fixed"), std::string::npos)
      << msg;
}

TEST(NetworkLoader, NetworkAndSingleFormTogetherAreRefused) {
  const std::string msg = errorOf(std::string(kNet) + "platform: {mass: 1.0}\n");
  EXPECT_NE(msg.find("net.yaml:26:11: platform: give platforms"), std::string::npos) << msg;
}

TEST(NetworkLoader, ScaledNetworkIsRefused) {
  const std::string msg = errorOf(withLine(kNet, 1, "units: scaled"));
  EXPECT_NE(msg.find("net.yaml:3:1: platforms"), std::string::npos) << msg;
}

// A one-platform network written from yaml/rigs/experiment.yaml's values.
const char* const kOne = R"(units: physical
name: experiment
platforms:
  - name: board
    mass: 0.1432
    friction: {law: coulomb, mu: 6.5e-4}
    metronomes:
      - {name: A, box_mass: 0.0602, pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}, escapement: {angle: 0.244, steady_amplitude: 0.785}, start: {angle: 0.785, rate: 0.0}}
      - {name: B, box_mass: 0.0602, pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}, escapement: {angle: 0.244, steady_amplitude: 0.785}, start: {angle: -0.785, rate: 0.25}}
simulation:
  duration: 200
)";

TEST(NetworkLoader, OnePlatformNetworkIsTodaysRigExactly) {
  const Rig today = defaultRig();
  const Network net = loadNetworkText(kOne, "one.yaml");
  ASSERT_TRUE(net.isSingleRig());
  expectSameRig(net.toSingleRig(), today);
  // and the single-platform loader takes it as that rig (every command runs it unchanged)
  expectSameRig(loadRigText(kOne, "one.yaml"), today);
  // today's form loads as a network of one
  const Network back = loadNetworkText(defaultRigYaml(), "experiment.yaml");
  ASSERT_TRUE(back.isSingleRig());
  expectSameRig(back.toSingleRig(), today);
}

TEST(NetworkLoader, SinglePlatformCommandsRefuseARealNetwork) {
  try {
    loadRigText(kNet, "net.yaml");
    FAIL() << "a network of three platforms loaded as one rig";
  } catch (const RigError& e) {
    EXPECT_NE(std::string(e.what()).find("net.yaml:4:3: platforms: a network of 3 platforms"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace metrosync

namespace metrosync {
namespace {

TEST(NetworkLoader, ShippedNetworkRigsLoad) {
  const std::string dir = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/";
  const Network swings = loadNetworkFile(dir + "two-swings.yaml");
  ASSERT_EQ(swings.platforms.size(), 2u);
  EXPECT_EQ(swings.platforms[0].rig.metronomes.size(), 15u);
  EXPECT_EQ(swings.platforms[1].rig.metronomes.size(), 15u);
  // the swing as a ground spring: k = M_total g / L_s with L_s = 0.5 m (the file's estimate)
  EXPECT_NEAR(swings.platforms[0].rig.platform.spring_N_m,
              swings.platforms[0].rig.totalMass() * 9.81 / 0.5, 0.5);
  const Network boards = loadNetworkFile(dir + "two-boards-rollers.yaml");
  EXPECT_EQ(boards.couplings.size(), 1u);
  const Network one = loadNetworkFile(dir + "board-on-springs.yaml");
  EXPECT_TRUE(one.isSingleRig());
  EXPECT_GT(one.toSingleRig().platform.spring_N_m, 0.0);
}

}  // namespace
}  // namespace metrosync
