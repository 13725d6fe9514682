// Sensible ranges of a physical rig (issue 37, yaml/sensible_ranges.h, docs/sensible-ranges.md):
// a unit typed wrong is found and named with the key, the value as typed and the range; every
// shipped rig outside yaml/rigs/hard/ is inside every range; the page and the code's table agree.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/number_text.h"
#include "yaml/rig_loader.h"
#include "yaml/sensible_ranges.h"

namespace metrosync {
namespace {

namespace fs = std::filesystem;
const std::string kSource = METROSYNC_SOURCE_DIR;

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<RangeFinding> findings(const std::vector<std::string>& sets) {
  return sensibleRangeFindings(defaultRigYaml(), "<default rig>", sets);
}

// The two: 22.5 for a pendulum of 22.5 mm, 143.2 for a board of 143.2 g.
TEST(SensibleRanges, AUnitTypedWrongIsNamedWithItsKeyValueAndRange) {
  EXPECT_TRUE(findings({}).empty()) << "the paper's rig is inside every range";
  const auto mm = findings({"metronomes.0.pendulum.length=22.5"});
  ASSERT_EQ(mm.size(), 1u);
  EXPECT_EQ(mm[0].key, "metronomes.0.pendulum.length");
  EXPECT_EQ(mm[0].message,
            "<default rig>: --set metronomes.0.pendulum.length=22.5: metronomes.0.pendulum.length "
            "= 22.5 m: outside 0.005 .. 0.5 m, the range of tabletop metronomes (in millimetres? "
            "the key is in metres; docs/sensible-ranges.md)");
  const auto g = findings({"platform.mass=143.2", "metronomes.1.escapement.angle=14"});
  ASSERT_EQ(g.size(), 2u);
  EXPECT_EQ(g[0].key, "platform.mass");
  EXPECT_NE(g[0].message.find("platform.mass = 143.2 kg: outside 0.01 .. 20 kg, the range of "
                              "tabletop boards (in grams? the key is in kilograms"),
            std::string::npos)
      << g[0].message;
  EXPECT_NE(g[1].message.find("metronomes.1.escapement.angle = 14 rad: outside 0 .. 1 rad"),
            std::string::npos)
      << g[1].message;
  EXPECT_NE(g[1].message.find("in degrees? the key is in radians"), std::string::npos);
  // in the file: located at the value's line and column
  const std::string text =
      defaultRigYaml().replace(defaultRigYaml().find("length: 0.0225"), 14, "length: 22.5  ");
  const auto in_file = sensibleRangeFindings(text, "rig.yaml", {});
  ASSERT_EQ(in_file.size(), 1u);
  EXPECT_EQ(in_file[0].message.rfind("rig.yaml:15:15: metronomes.0.pendulum.length = 22.5 m", 0),
            0u)
      << in_file[0].message;
}

// Each bound is inclusive; a value a hair outside is found, one at the bound is not.
TEST(SensibleRanges, BoundsAreInclusive) {
  for (const SensibleRange& r : sensibleRanges()) {
    if (r.scope != SensibleRange::Scope::Metronome) continue;
    const std::string key = std::string("metronomes.0.") + r.key;
    EXPECT_TRUE(findings({key + "=" + roundTripText(r.hi)}).empty()) << key;
    EXPECT_EQ(findings({key + "=" + roundTripText(r.hi * 1.01 + 1e-9)}).size(), 1u) << key;
  }
  EXPECT_TRUE(sensibleRangeFindings(slurp(kSource + "/yaml/rigs/experiment-scaled.yaml"),
                                    "scaled.yaml", {"metronomes.0.J=1e6"})
                  .empty())
      << "a scaled rig is not checked";
}

// A network's platforms and their metronomes are checked under their own keys.
TEST(SensibleRanges, ANetworkIsCheckedPlatformByPlatform) {
  const std::string path = kSource + "/yaml/rigs/two-swings.yaml";
  const auto f = sensibleRangeFindings(slurp(path), path,
                                       {"platforms.right.mass=500",
                                        "platforms.0.metronomes.3."
                                        "pendulum.mass=20"});
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[0].key, "platforms.0.metronomes.3.pendulum.mass");
  EXPECT_EQ(f[1].key, "platforms.1.mass");
}

// The ranges hold every real rig the project ships: only the deliberately extreme hard/ rigs may
// fall outside.
TEST(SensibleRanges, EveryShippedRigOutsideHardIsInside) {
  int physical = 0;
  for (const auto& e : fs::recursive_directory_iterator(kSource + "/yaml/rigs")) {
    const std::string p = e.path().string();
    if (e.path().extension() != ".yaml" || p.find("/hard/") != std::string::npos) continue;
    const std::string text = slurp(p);
    physical += text.find("units: physical") != std::string::npos;
    for (const RangeFinding& f : sensibleRangeFindings(text, p, {})) ADD_FAILURE() << f.message;
  }
  EXPECT_GE(physical, 15);
  // and hard/storm.yaml's 3e19 N/m spring is far outside, on purpose
  const std::string storm = kSource + "/yaml/rigs/hard/storm.yaml";
  ASSERT_EQ(sensibleRangeFindings(slurp(storm), storm, {}).size(), 1u);
}

// docs/sensible-ranges.md's table is the code's, row for row.
TEST(SensibleRanges, ThePageListsEveryRangeOfTheCode) {
  const std::string page = slurp(kSource + "/docs/sensible-ranges.md");
  for (const SensibleRange& r : sensibleRanges()) {
    const char* where = r.scope == SensibleRange::Scope::Top     ? "top"
                        : r.scope == SensibleRange::Scope::Board ? "board"
                                                                 : "metronome";
    const std::string row = "| `" + std::string(r.key) + "` | " + where + " | " + numberText(r.lo) +
                            " .. " + numberText(r.hi) + " | " + r.unit + " | " + r.paper + " |";
    EXPECT_NE(page.find(row), std::string::npos) << "missing row: " << row;
  }
}

}  // namespace
}  // namespace metrosync
