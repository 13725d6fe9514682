// Item 4 of issue 17: every string that can reach a file is UTF-8, checked at load time with its
// location: the rig's text, its escapes, --set values; names are bounded and free of control
// characters.
#include "tests/hostile/hostile_support.h"
#include "yaml/utf8.h"

namespace metrosync::hostile {
namespace {

// Unicode table 3-7: the boundaries of well-formed UTF-8.
TEST(HostileText, Utf8BoundariesOfTableThreeSeven) {
  const std::vector<std::pair<std::string, std::optional<std::size_t>>> cases = {
      {"plain", std::nullopt},
      {"caf\xC3\xA9", std::nullopt},       // U+00E9
      {"\xEF\xBF\xBF", std::nullopt},      // U+FFFF
      {"\xF4\x8F\xBF\xBF", std::nullopt},  // U+10FFFF, the last code point
      {"\xED\x9F\xBF", std::nullopt},      // U+D7FF, just below the surrogates
      {"ab\xE9", 2},                       // Latin-1 e-acute
      {"\xC0\xAF", 0},                     // overlong '/'
      {"\xE0\x80\xAF", 0},                 // overlong, three bytes
      {"\xED\xA0\x80", 0},                 // U+D800, a surrogate
      {"\xF4\x90\x80\x80", 0},             // U+110000
      {"x\xC3", 1},                        // cut short
      {"\xFF", 0},
  };
  for (const auto& [s, bad] : cases) EXPECT_EQ(firstBadUtf8(s), bad) << printable(s);
  EXPECT_EQ(printable("a\xFF\x01"
                      "b\xC3\xA9"),
            "a\\xFF\\x01b\xC3\xA9");
}

TEST(HostileText, RigTextIsUtf8WithItsLocation) {
  const std::string rig = shippedRig("experiment.yaml");
  // line 5 of the rig is "name: experiment": a Latin-1 byte in the name, at column 10
  std::string latin1 = rig;
  latin1.replace(latin1.find("name: experiment"), 16, "name: caf\xE9");
  EXPECT_EQ(loadError(latin1).rfind("rig.yaml:5:10: not UTF-8 text (byte 0xE9)", 0), 0u)
      << loadError(latin1);
  // columns count characters: two 2-byte characters before the bad byte
  std::string wide = rig;
  wide.replace(wide.find("name: experiment"), 16, "name: \xC3\xA9\xC3\xA9\xFF");
  EXPECT_EQ(loadError(wide).rfind("rig.yaml:5:9: not UTF-8", 0), 0u) << loadError(wide);
  // a NUL byte and a control character
  std::string nul = rig;
  nul.replace(nul.find("name: experiment"), 16, std::string("name: a\0b", 9));
  EXPECT_EQ(loadError(nul).rfind("rig.yaml:5:8: a NUL byte", 0), 0u) << loadError(nul);
  // an escape that makes a NUL inside a name: a name cannot hold control characters
  EXPECT_NE(loadError(rig, {"name=\"a\\0b\""}).find("must not contain control characters"),
            std::string::npos);
}

TEST(HostileText, SetValuesAreUtf8) {
  const std::string rig = shippedRig("experiment.yaml");
  const std::string msg = loadError(rig, {"name=ok", "name=\xFF"});
  EXPECT_EQ(msg, "rig.yaml: --set name=\\xFF: not UTF-8 text (byte 6 of the --set)");
  const std::string metronome = loadError(rig, {"metronomes.1.name=\xC3"});
  EXPECT_EQ(metronome.rfind("rig.yaml: --set metronomes.1.name=\\xC3: not UTF-8", 0), 0u)
      << metronome;
}

TEST(HostileText, NamesAreBounded) {
  const std::string rig = shippedRig("experiment.yaml");
  const std::string at_limit = std::string(kMaxNameBytes, 'n');
  EXPECT_EQ(loadRigText(rig, "r", {"name=" + at_limit}).name, at_limit);
  const std::string over = loadError(rig, {"name=" + at_limit + "n"});
  EXPECT_NE(over.find("is " + std::to_string(kMaxNameBytes + 1) + " bytes long"), std::string::npos)
      << over;
  const std::string metronome = loadError(rig, {"metronomes.0.name=" + at_limit + "n"});
  EXPECT_NE(metronome.find("metronomes.0.name = "), std::string::npos) << metronome;
}

// Before issue 17 a non-UTF-8 name ran the whole simulation and then failed writing
// summary.json (exit 1, files left behind); now nothing is written.
TEST(HostileText, NothingIsWrittenForABadName) {
  const std::string out = testing_support::scratchDir("hostile", "badname");
  for (const std::string cmd : {"run", "compare"}) {
    const CommandResult r = runLimited(cmd + " --set 'metronomes.0.name=\xE9t\xE9'", out);
    expectRefusedCleanly(r, out, cmd);
  }
}

}  // namespace
}  // namespace metrosync::hostile
