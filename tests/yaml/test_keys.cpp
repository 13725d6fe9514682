// The one key language (issue 24, docs/keys.md): `*` in a --set sets every element exactly as one
// --set per index would, a platform's name stands for its index, `metronomes.*` on a network is
// every metronome of every platform, and a bad key gets the same words whichever option typed it.
// The resolved rig (resolvedRigJson: the whole tree after the overrides) is the witness of "the
// same rig": two override lists that give the same text set the same keys to the same values.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "yaml/key_path.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

const char* const kPhysical = R"(units: physical
platform:
  mass: 0.15
  friction: {law: coulomb, mu: 6.5e-4}
metronomes:
  - box_mass: 0.06
    pendulum: {mass: 0.0226, length: 0.0225, damping: 0.0226}
    escapement: {angle: 0.244, impulse: 1.5e-5}
  - box_mass: 0.06
    pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}
    escapement: {angle: 0.244, steady_amplitude: 0.785}
    start: {angle: 0.5, rate: 0.0}
  - box_mass: 0.07
    pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}
    escapement: {angle: 0.244, steady_amplitude: 0.785}
simulation:
  duration: 10
)";

const char* const kScaled = R"(units: scaled
epsilon: 0.073
platform:
  friction: {law: coulomb, mu: 0.4}
metronomes:
  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: 1.9, phi: 0.03}}
  - {nu: 0.6, J: 2.8, theta_c: 0.9, alpha: 0.1}
simulation:
  tau: 30
)";

// Two platforms named left and right (of two and one metronomes), coupled by a spring.
const char* const kNetwork = R"(units: physical
platforms:
  - name: left
    mass: 0.15
    friction: {law: coulomb, mu: 6.5e-4}
    metronomes:
      - {box_mass: 0.06, pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}, escapement: {angle: 0.244, steady_amplitude: 0.785}, start: {angle: 0.7}}
      - {box_mass: 0.06, pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}, escapement: {angle: 0.244, steady_amplitude: 0.785}}
  - name: right
    mass: 0.15
    friction: {law: coulomb, mu: 6.5e-4}
    metronomes:
      - {box_mass: 0.06, pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}, escapement: {angle: 0.244, steady_amplitude: 0.785}}
couplings:
  - {between: [left, right], k: 2.0}
simulation:
  duration: 10
)";

std::string resolved(const std::string& text, const std::vector<std::string>& sets) {
  return resolvedRigJson(text, "rig.yaml", sets);
}

// The RigError message of loading `text` with `sets` ("" and a failure if it loads).
std::string loadError(const std::string& text, const std::vector<std::string>& sets) {
  try {
    resolved(text, sets);
  } catch (const RigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "loaded";
  return "";
}

std::vector<std::string> texts(const std::vector<KeyPath>& paths) {
  std::vector<std::string> t;
  for (const KeyPath& p : paths) t.push_back(p.text());
  return t;
}

TEST(KeyPath, ParsesNamesIndicesAndWildcards) {
  const KeyPath k = KeyPath::parse(" metronomes.*.start.12 ");
  EXPECT_EQ(k.text(), "metronomes.*.start.12");
  ASSERT_EQ(k.size(), 4u);
  EXPECT_EQ(k[0].kind, KeyPath::Segment::Kind::Name);
  EXPECT_EQ(k[1].kind, KeyPath::Segment::Kind::Every);
  EXPECT_EQ(k[3].kind, KeyPath::Segment::Kind::Index);
  EXPECT_EQ(k[3].index, 12u);
  EXPECT_TRUE(k.hasWildcard());
  EXPECT_EQ(k.leaf(), "12");
  EXPECT_EQ(k.parent(), "start");
  EXPECT_EQ(k.prefix(2), "metronomes.*");
  EXPECT_FALSE(KeyPath::parse("platforms.left.friction.mu").hasWildcard());
  const KeyAssignment a = parseAssignment("metronomes.*.nu=a=b");
  EXPECT_EQ(a.key.text(), "metronomes.*.nu");
  EXPECT_EQ(a.value, "a=b");  // the value is everything after the first '='
  for (const char* bad : {"", " ", "a..b", "a.", ".a", "a.b*.c", "a.**", "m.123456789", "a.b=1"})
    EXPECT_THROW(KeyPath::parse(bad), KeyError) << bad;
  for (const char* bad : {"a.b", "=1", " =1"}) EXPECT_THROW(parseAssignment(bad), KeyError) << bad;
}

// `*` sets every element, exactly as one --set per index: the resolved rigs are the same text.
TEST(KeyResolver, WildcardSetIsEverySetIndex) {
  EXPECT_EQ(
      resolved(kPhysical, {"metronomes.*.pendulum.mass=0.03"}),
      resolved(kPhysical, {"metronomes.0.pendulum.mass=0.03", "metronomes.1.pendulum.mass=0.03",
                           "metronomes.2.pendulum.mass=0.03"}));
  // a key absent from some elements (start) is created in each, a whole map replaces each
  EXPECT_EQ(resolved(kPhysical, {"metronomes.*.start.rate=0.25",
                                 "metronomes.*.escapement={angle: 0.2, impulse: 1e-5}"}),
            resolved(kPhysical, {"metronomes.0.start.rate=0.25", "metronomes.1.start.rate=0.25",
                                 "metronomes.2.start.rate=0.25",
                                 "metronomes.0.escapement={angle: 0.2, impulse: 1e-5}",
                                 "metronomes.1.escapement={angle: 0.2, impulse: 1e-5}",
                                 "metronomes.2.escapement={angle: 0.2, impulse: 1e-5}"}));
  EXPECT_EQ(resolved(kScaled, {"metronomes.*.nu=0.55"}),
            resolved(kScaled, {"metronomes.0.nu=0.55", "metronomes.1.nu=0.55"}));
  // and it did set them: the rig differs from the file's
  EXPECT_NE(resolved(kScaled, {"metronomes.*.nu=0.55"}), resolved(kScaled, {}));
  // the same through the built rig
  const Rig rig = loadRigText(kPhysical, "rig.yaml", {"metronomes.*.box_mass=0.05"});
  for (const MetronomeSpec& m : rig.metronomes) EXPECT_EQ(m.box_mass_kg, 0.05);
}

TEST(KeyResolver, PlatformNamesResolveToTheirIndices) {
  EXPECT_EQ(resolved(kNetwork, {"platforms.right.friction.mu=0.01"}),
            resolved(kNetwork, {"platforms.1.friction.mu=0.01"}));
  EXPECT_EQ(resolved(kNetwork, {"platforms.left.metronomes.1.start.angle=-0.3"}),
            resolved(kNetwork, {"platforms.0.metronomes.1.start.angle=-0.3"}));
  EXPECT_NE(resolved(kNetwork, {"platforms.right.friction.mu=0.01"}), resolved(kNetwork, {}));
  // `*` over the platforms, and over the metronomes of a named one
  EXPECT_EQ(resolved(kNetwork, {"platforms.*.mass=0.2"}),
            resolved(kNetwork, {"platforms.0.mass=0.2", "platforms.1.mass=0.2"}));
  EXPECT_EQ(resolved(kNetwork, {"platforms.left.metronomes.*.box_mass=0.05"}),
            resolved(kNetwork, {"platforms.0.metronomes.0.box_mass=0.05",
                                "platforms.0.metronomes.1.box_mass=0.05"}));
}

// On a network `metronomes.*.X` is every metronome of every platform.
TEST(KeyResolver, NetworkMetronomesWildcardIsEveryMetronome) {
  const std::string every = resolved(kNetwork, {"metronomes.*.box_mass=0.05"});
  EXPECT_EQ(every, resolved(kNetwork, {"platforms.*.metronomes.*.box_mass=0.05"}));
  EXPECT_EQ(every, resolved(kNetwork, {"platforms.0.metronomes.0.box_mass=0.05",
                                       "platforms.0.metronomes.1.box_mass=0.05",
                                       "platforms.1.metronomes.0.box_mass=0.05"}));
  const RigKey k = resolveRigKey(kNetwork, "rig.yaml", {}, "metronomes.*.start.angle", "--vary ..");
  EXPECT_TRUE(k.group());
  EXPECT_EQ(texts(k.paths), (std::vector<std::string>{"platforms.0.metronomes.0.start.angle",
                                                      "platforms.0.metronomes.1.start.angle",
                                                      "platforms.1.metronomes.0.start.angle"}));
  // one metronome of a network is named through its platform
  EXPECT_NE(loadError(kNetwork, {"metronomes.0.box_mass=0.05"})
                .find("a network's metronomes are under its platforms"),
            std::string::npos);
}

// What an option's key stands for: the concrete paths, a wildcard's kept together as a group
// (what `fit --free metronomes.*.X` receives).
TEST(KeyResolver, OptionKeysResolveToConcretePaths) {
  const RigKey every =
      resolveRigKey(kPhysical, "rig.yaml", {}, "metronomes.*.pendulum.damping", "--free ..");
  EXPECT_TRUE(every.group());
  EXPECT_EQ(every.key.text(), "metronomes.*.pendulum.damping");
  EXPECT_EQ(texts(every.paths), (std::vector<std::string>{"metronomes.0.pendulum.damping",
                                                          "metronomes.1.pendulum.damping",
                                                          "metronomes.2.pendulum.damping"}));
  const RigKey one = resolveRigKey(kNetwork, "rig.yaml", {}, "platforms.right.friction.mu", "x");
  EXPECT_FALSE(one.group());
  EXPECT_EQ(texts(one.paths), (std::vector<std::string>{"platforms.1.friction.mu"}));
  // the list the wildcard runs over is the rig's after --set
  EXPECT_EQ(resolveRigKey(kScaled, "rig.yaml", {"metronomes=[{nu: 1, J: 2, theta_c: 0.9}]"},
                          "metronomes.*.nu", "x")
                .paths.size(),
            1u);
  EXPECT_EQ(
      sharedPath(
          every.paths,
          resolveRigKey(kPhysical, "rig.yaml", {}, "metronomes.1.pendulum.damping", "x").paths),
      "metronomes.1.pendulum.damping");
  // a key inside another: both set it; siblings with a common prefix do not
  const auto paths = [](const char* key) {
    return resolveRigKey(kPhysical, "rig.yaml", {}, key, "x").paths;
  };
  EXPECT_EQ(sharedPath(paths("platform.friction"), paths("platform.friction.mu")),
            "platform.friction.mu");
  EXPECT_EQ(sharedPath(paths("metronomes.1"), paths("metronomes.*.box_mass")),
            "metronomes.1.box_mass");
  EXPECT_EQ(sharedPath(paths("platform.mass"), paths("platform.friction.mu")), "");
  EXPECT_EQ(sharedPath({KeyPath::parse("a.rate")}, {KeyPath::parse("a.rat")}), "");
  // the number at a key, and at a wildcard's first element
  EXPECT_EQ(rigNumber(kPhysical, "rig.yaml", {}, "metronomes.1.start.angle"), 0.5);
  EXPECT_EQ(rigNumber(kScaled, "rig.yaml", {}, "metronomes.*.nu"), 0.7);
}

// A single-platform rig is a network of one platform named "platform" (issue 38): every key that
// names a platform of a network works on it -- platforms.0..., platforms.platform...,
// platforms.*... set exactly the rig's own keys -- and another platform is refused naming the one
// it has. (On main these keys made a `platforms` list the rig does not have and were refused.)
TEST(KeyResolver, SingleRigAnswersTheKeysOfItsOnePlatform) {
  const std::vector<std::pair<std::string, std::string>> same = {
      {"platforms.0.friction.mu=0.01", "platform.friction.mu=0.01"},
      {"platforms.platform.friction.mu=0.01", "platform.friction.mu=0.01"},
      {"platforms.*.friction={law: viscous, c: 0.2}", "platform.friction={law: viscous, c: 0.2}"},
      {"platforms.platform.metronomes.1.start.angle=0.3", "metronomes.1.start.angle=0.3"},
      {"platforms.0.metronomes.*.box_mass=0.08", "metronomes.*.box_mass=0.08"},
      {"platforms.0.mass=0.2", "platform.mass=0.2"},
      {"platforms.platform.spring.k=3", "platform.spring.k=3"},
      {"platforms.0.start.x=0.001", "start.x=0.001"}};
  for (const auto& [network, own] : same) {
    EXPECT_EQ(resolved(kPhysical, {network}), resolved(kPhysical, {own})) << network;
    EXPECT_NE(resolved(kPhysical, {network}), resolved(kPhysical, {})) << network;
  }
  EXPECT_EQ(resolved(kScaled, {"platforms.platform.metronomes.*.nu=0.5"}),
            resolved(kScaled, {"metronomes.*.nu=0.5"}));
  EXPECT_EQ(resolved(kScaled, {"platforms.0.friction.mu=0.2"}),
            resolved(kScaled, {"platform.friction.mu=0.2"}));
  // the name the loader gives the one platform is the name the keys answer to
  EXPECT_EQ(loadNetworkText(kPhysical, "rig.yaml").platforms.at(0).name, kSinglePlatformName);
  // an option's key resolves to the rig's own paths
  const RigKey k = resolveRigKey(kPhysical, "rig.yaml", {},
                                 "platforms.platform.metronomes.*.pendulum.mass", "--vary ...");
  EXPECT_EQ(texts(k.paths),
            (std::vector<std::string>{"metronomes.0.pendulum.mass", "metronomes.1.pendulum.mass",
                                      "metronomes.2.pendulum.mass"}));
  EXPECT_TRUE(k.group());
}

TEST(KeyResolver, SingleRigRefusesAPlatformItDoesNotHave) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"platforms.left.friction.mu=0.01",
       "platforms.left: no entry of platforms is named 'left' (names: platform;"},
      {"platforms.1.friction.mu=0.01", "platforms.1: index 1 is out of range"},
      {"platforms.0.name=board",
       "platforms.0.name: a single-platform rig's platform is named "
       "'platform'"},
      {"platforms.0.on=table",
       "platforms.0.on: a single-platform rig's platform rests on the "
       "table"},
      {"platforms.0={mass: 1}", "platforms.0: a single-platform rig's platform is set key by key"},
      {"platforms.0.spring.c=1",
       "platforms.0.spring.c is platform.spring.c on this single-platform rig: "
       "platform.spring.c: unknown key"}};
  for (const auto& [set, why] : bad) {
    const std::string e = loadError(kPhysical, {set});
    EXPECT_EQ(e.rfind("rig.yaml: --set " + set + ": ", 0), 0u) << e;
    EXPECT_NE(e.find(why), std::string::npos) << e;
  }
  // scaled: its platform has no mass, said in the scaled rig's words
  EXPECT_NE(loadError(kScaled, {"platforms.0.mass=1"}).find("platform.mass"), std::string::npos);
  EXPECT_NE(loadError(kScaled, {"platforms.right.friction.mu=1"}).find("(names: platform;"),
            std::string::npos);
}

// The same bad key gets the same words from a --set as from any other option, after what the
// user typed.
TEST(KeyResolver, BadKeysSayTheSameWhateverTheOption) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"metronomes.*.nuu", "metronomes.*.nuu: unknown key (did you mean 'nu'?)"},
      {"metronomes.5.nu", "metronomes.5: index 5 is out of range (metronomes has 2 entries"},
      {"metronomes.first.nu", "metronomes is a list: expected an index from 0, or * for every"},
      {"platform.*.mu", "'*' stands for every element of a list, and platform is a map"},
      {"metronomes.*.*", "metronomes.*.*: '*' stands for every element of a list"},
      {"metronomes..nu", "'metronomes.': empty key"},
      {"metronomes.n*.nu", "'*' stands alone between dots"},
  };
  for (const auto& [key, why] : bad) {
    const std::string set = loadError(kScaled, {key + "=1"});
    EXPECT_EQ(set.rfind("rig.yaml: --set " + key + "=1: ", 0), 0u) << set;
    EXPECT_NE(set.find(why), std::string::npos) << set;
    const std::string tail = set.substr(set.find("=1: ") + 4);
    for (const std::string& typed : {"--vary " + key + "=0:1:3", "--free " + key}) {
      try {
        resolveRigKey(kScaled, "rig.yaml", {}, key, typed);
        ADD_FAILURE() << typed << " resolved";
      } catch (const RigError& e) {
        EXPECT_EQ(std::string(e.what()), "rig.yaml: " + typed + ": " + tail);
      }
    }
  }
  EXPECT_NE(loadError(kNetwork, {"platforms.middle.mass=1"})
                .find("platforms.middle: no entry of platforms is named 'middle' (names: left, "
                      "right)"),
            std::string::npos);
  EXPECT_NE(loadError(kScaled, {"couplings.*.k=1"}).find("only with units: physical"),
            std::string::npos);
  EXPECT_NE(loadError(kPhysical, {"couplings.*.k=1"})
                .find("couplings.*: couplings has no entries for '*' to stand for"),
            std::string::npos);
  // a value the wildcard sets wrong is quoted as typed, the element named
  const std::string value = loadError(kScaled, {"metronomes.*.nu=abc"});
  EXPECT_EQ(value.rfind("rig.yaml: --set metronomes.*.nu=abc: metronomes.0.nu = abc: must be a "
                        "number",
                        0),
            0u)
      << value;
}

}  // namespace
}  // namespace metrosync
