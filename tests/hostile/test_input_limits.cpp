// Items 1 and 2 of issue 17: no YAML input costs more than a small multiple of its size (aliases
// refused, a node budget, a depth limit), rig paths are checked before reading, and the number of
// metronomes is bounded. Limits are checked at their exact boundary.
#include <fstream>

#include "tests/hostile/hostile_support.h"
#include "yaml/rig_tree.h"

namespace metrosync::hostile {
namespace {

namespace fs = std::filesystem;

TEST(HostileInput, AliasesAreRefusedWhereTheyAre) {
  // nine levels of nine aliases: 9^9 = 387 million nodes if expanded
  std::string bomb = "units: physical\na: &a [lol, lol, lol]\n";
  for (char c = 'b'; c <= 'j'; ++c) {
    const char prev = static_cast<char>(c - 1);
    bomb += std::string(1, c) + ": &" + c + " [*" + prev + ", *" + prev + ", *" + prev + "]\n";
  }
  const std::string msg = loadError(bomb);
  EXPECT_EQ(msg.rfind("rig.yaml:3:8: an alias (*name)", 0), 0u) << msg;
  // an anchor alone is harmless; a value aliased from a --set is refused at the --set
  const std::string rig = shippedRig("experiment.yaml");
  const std::string set_msg = loadError(rig, {"platform.friction=[&a [1], *a]"});
  EXPECT_EQ(set_msg.rfind("rig.yaml: --set platform.friction=[&a [1], *a]: ", 0), 0u) << set_msg;
  EXPECT_NE(set_msg.find("alias"), std::string::npos) << set_msg;
}

// "units: physical\nx: [1, 1, ...]": the root map, two keys, two values and the list's k items.
std::string listOf(int k) {
  std::string s = "units: physical\nx: [";
  for (int i = 0; i < k; ++i) s += i ? ",1" : "1";
  return s + "]\n";
}

TEST(HostileInput, NodeBudgetAtItsBoundary) {
  const int fixed = 5;  // map, "units", "physical", "x", the list
  const std::string at_limit = loadError(listOf(kMaxYamlNodes - fixed));
  EXPECT_EQ(at_limit.find("YAML nodes"), std::string::npos) << at_limit;
  EXPECT_NE(at_limit.find("rig.yaml:2:1: x: unknown key"), std::string::npos) << at_limit;
  const std::string over = loadError(listOf(kMaxYamlNodes - fixed + 1));
  EXPECT_NE(over.find("more than " + std::to_string(kMaxYamlNodes) + " YAML nodes"),
            std::string::npos)
      << over;
  EXPECT_TRUE(located(over, "rig.yaml")) << over;
}

// A root map holding `depth - 1` nested lists: `depth` levels of collections.
std::string nested(int depth) {
  return "units: physical\nx: " + std::string(depth - 1, '[') + std::string(depth - 1, ']') + "\n";
}

TEST(HostileInput, DepthLimitAtItsBoundary) {
  const std::string at_limit = loadError(nested(kMaxYamlDepth));
  EXPECT_EQ(at_limit.find("nested more than"), std::string::npos) << at_limit;
  const std::string over = loadError(nested(kMaxYamlDepth + 1));
  // the innermost list opens at column 4 + kMaxYamlDepth - 1 of line 2
  EXPECT_EQ(over.rfind("rig.yaml:2:" + std::to_string(4 + kMaxYamlDepth - 1) + ": nested more", 0),
            0u)
      << over;
  // far deeper than yaml-cpp's own recursion guard: still our message, not "bad file"
  const std::string deep = loadError(nested(100000));
  EXPECT_NE(deep.find("nested more than"), std::string::npos) << deep.substr(0, 200);
}

// The experiment rig with its metronome list replaced by `n` copies of metronome A.
std::string rigWithMetronomes(std::size_t n) {
  const std::string rig = shippedRig("experiment.yaml");
  const std::size_t list = rig.find("metronomes:\n"), sim = rig.find("simulation:");
  std::string text = rig.substr(0, list) + "metronomes:\n";
  const std::string one =
      "  - {box_mass: 0.0602, pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}, "
      "escapement: {angle: 0.244, steady_amplitude: 0.785}, start: {angle: 0.3}}\n";
  for (std::size_t i = 0; i < n; ++i) text += one;
  return text + rig.substr(sim);
}

TEST(HostileInput, MetronomeBoundAtItsBoundary) {
  // 20 s keeps the load cheap (the output estimate grows with the run; it is not the point here)
  const Rig rig =
      loadRigText(rigWithMetronomes(kMaxMetronomes), "many.yaml", {"simulation.duration=20"});
  EXPECT_EQ(rig.metronomes.size(), kMaxMetronomes);
  const std::string over = loadError(rigWithMetronomes(kMaxMetronomes + 1));
  EXPECT_NE(over.find("holds " + std::to_string(kMaxMetronomes + 1) + " metronomes (at most " +
                      std::to_string(kMaxMetronomes)),
            std::string::npos)
      << over.substr(0, 300);
  EXPECT_TRUE(located(over, "rig.yaml")) << over.substr(0, 300);
}

std::string readError(const std::string& path) {
  try {
    readRigFile(path);
  } catch (const RigError& e) {
    return e.what();
  }
  return "";
}

TEST(HostileInput, RigPathIsCheckedBeforeReading) {
  const std::string scratch = testing_support::scratchDir("hostile", "path", true);
  EXPECT_EQ(readError(scratch), scratch +
                                    ": is a directory, not a rig file (a rig is a regular "
                                    "YAML file)");
  EXPECT_NE(readError("/dev/zero").find("/dev/zero: is a device"), std::string::npos);
  EXPECT_NE(readError("/dev/null").find("/dev/null: is a device"), std::string::npos);

  // exactly at the size limit: read in full (and then a YAML matter); one byte more: refused
  const std::string at = scratch + "/at.yaml", over = scratch + "/over.yaml";
  {
    std::ofstream a(at, std::ios::binary), o(over, std::ios::binary);
    const std::string filler(kMaxRigFileBytes, '#');
    a << filler;
    o << filler << '#';
  }
  EXPECT_EQ(readRigFile(at).size(), kMaxRigFileBytes);
  EXPECT_NE(readError(over).find("is " + std::to_string(kMaxRigFileBytes + 1) + " bytes, above"),
            std::string::npos)
      << readError(over);
  fs::remove_all(scratch);
}

}  // namespace
}  // namespace metrosync::hostile
