// summary.json's resolved_rig (resolvedRigJson) written through nlohmann-json keeps summary.json's
// bytes: for every shipped rig and for --set values at the edges of number formatting, the JSON
// it parses to is the one the former hand-written writer's text parsed to (that writer, %.17g
// numbers, is kept here as the reference), key order and integer/float kinds included.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "yaml/rig_build.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

// ---- the former writer (yaml/rig_loader.cpp before nlohmann-json), the reference ----
void appendString(std::string& out, const std::string& s) {
  out += '"';
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  out += '"';
}

void appendTree(std::string& out, const Node& n) {
  if (n.kind == Node::Kind::Null) {
    out += "null";
  } else if (n.kind == Node::Kind::Scalar) {
    const std::optional<double> v = parseRigNumber(n.scalar);
    if (v && std::isfinite(*v)) {
      char buf[40];
      std::snprintf(buf, sizeof buf, "%.17g", *v);
      out += buf;
    } else {
      appendString(out, n.scalar);
    }
  } else if (n.kind == Node::Kind::Map) {
    out += '{';
    for (std::size_t k = 0; k < n.map.size(); ++k) {
      if (k) out += ", ";
      appendString(out, n.map[k].key);
      out += ": ";
      appendTree(out, n.map[k].value);
    }
    out += '}';
  } else {
    out += '[';
    for (std::size_t k = 0; k < n.seq.size(); ++k) {
      if (k) out += ", ";
      appendTree(out, n.seq[k]);
    }
    out += ']';
  }
}

std::string formerJson(const std::string& text, const std::string& name,
                       const std::vector<std::string>& sets) {
  Node root = checkedRigTree(text, RigSource{name, sets});
  if (!root.find("name")) {
    Entry e;
    e.key = "name";
    e.value.kind = Node::Kind::Scalar;
    e.value.scalar = rigStem(name);
    root.map.insert(root.map.begin(), std::move(e));
  }
  std::string out;
  appendTree(out, root);
  return out;
}
// ---------------------------------------------------------------------------------------------

// What summary.json holds: the text parsed (ordered: key order counts too) and dumped.
std::string asSummaryHoldsIt(const std::string& json_text) {
  return nlohmann::ordered_json::parse(json_text).dump();
}

void expectSameJson(const std::string& text, const std::string& name,
                    const std::vector<std::string>& sets) {
  const std::string now = resolvedRigJson(text, name, sets);
  EXPECT_EQ(asSummaryHoldsIt(now), asSummaryHoldsIt(formerJson(text, name, sets)));
  // and as summary.json itself (nlohmann::json, keys sorted) writes it
  EXPECT_EQ(nlohmann::json::parse(now).dump(2),
            nlohmann::json::parse(formerJson(text, name, sets)).dump(2));
}

std::string readText(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(ResolvedRigJson, EveryShippedRigParsesAsTheFormerWritersText) {
  const std::filesystem::path dir = std::filesystem::path(METROSYNC_SOURCE_DIR) / "yaml/rigs";
  int rigs = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (e.path().extension() != ".yaml") continue;
    SCOPED_TRACE(e.path().string());
    expectSameJson(readText(e.path()), e.path().filename().string(), {});
    ++rigs;
  }
  EXPECT_GE(rigs, 40);
}

// Integral values (JSON integers below 1e17, floats from 1e17), negative zero, tiny and huge
// numbers, a quote in a name, a map written by --set.
TEST(ResolvedRigJson, NumbersAtTheEdgesKeepTheirJsonKind) {
  const std::vector<std::vector<std::string>> cases = {
      {"simulation.duration=2.0", "platform.mass=1e16"},
      {"platform.mass=1e17", "start.x=-0"},
      {"start.v=1e-300", "name=q\"x"},
      {"platform.mass=123456789012345678"},
      {"metronomes.*.start.rate=-3", "platform.friction={law: coulomb, mu: 0.1, mu_static: 0.2}"},
      {"metronomes.0.start={angle: 0.5, rate: 1e-5}", "gravity=9.8000000000000007"}};
  for (const auto& sets : cases) {
    SCOPED_TRACE(sets.front());
    expectSameJson(defaultRigYaml(), "experiment.yaml", sets);
  }
  // the kinds themselves: "2.0" and "1e16" are integers, "1e17" a float, "-0" is 0
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(
      resolvedRigJson(defaultRigYaml(), "x.yaml", {"simulation.duration=2.0", "start.x=-0"}));
  EXPECT_EQ(j["simulation"]["duration"].dump(), "2");
  EXPECT_EQ(j["start"]["x"].dump(), "0");
  EXPECT_EQ(j["platform"]["friction"]["mu"].dump(), "0.00065");
}

// Changed on purpose (CHANGELOG): the text is nlohmann's compact form, numbers in their shortest
// exact decimal; it is still a rig file that loads to the same rig.
TEST(ResolvedRigJson, TheTextIsCompactAndLoadsToTheSameRig) {
  const std::string text = resolvedRigJson(defaultRigYaml(), "<default rig>", {});
  EXPECT_EQ(text.rfind(R"({"units":"physical","name":"experiment",)", 0), 0u) << text;
  EXPECT_NE(text.find(R"("mu":0.00065)"), std::string::npos) << text;
  const Rig a = defaultRig(), b = loadRigText(text, "again.yaml");
  EXPECT_EQ(a.platform.friction, b.platform.friction);
  EXPECT_EQ(a.metronomes[1].start_rate_rad_s, b.metronomes[1].start_rate_rad_s);
  EXPECT_EQ(a.metronomes[0].impulse_Nms, b.metronomes[0].impulse_Nms);
}

}  // namespace
}  // namespace metrosync
