// summary.json's resolved_rig: the rig's tree after the overrides as JSON, through nlohmann-json.
// Numbers are written as the value they read as; one that the former writer printed with %.17g
// as an integer (an integral value below 1e17 in magnitude) stays a JSON integer, so that
// summary.json, which parses this text, keeps its bytes (tests/yaml/test_rig_json.cpp).
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>

#include "yaml/rig_build.h"
#include "yaml/rig_loader.h"
#include "yaml/rig_reader.h"

namespace metrosync {

namespace {

using Json = nlohmann::ordered_json;  // keys in document order

// %.17g prints every integral double below 1e17 in magnitude without a point or an exponent
constexpr double kIntegerTextLimit = 1e17;

Json scalarJson(const std::string& scalar) {
  const std::optional<double> v = rigfile::parseNumber(scalar);
  if (!v || !std::isfinite(*v)) return Json(scalar);  // a name, or .inf/.nan as written
  if (std::trunc(*v) == *v && std::fabs(*v) < kIntegerTextLimit)
    return Json(static_cast<std::int64_t>(*v));
  return Json(*v);
}

Json treeJson(const Node& n) {
  switch (n.kind) {
    case Node::Kind::Null:
      return Json(nullptr);
    case Node::Kind::Scalar:
      return scalarJson(n.scalar);
    case Node::Kind::Map: {
      Json j = Json::object();
      for (const Entry& e : n.map) j[e.key] = treeJson(e.value);
      return j;
    }
    case Node::Kind::Seq: {
      Json j = Json::array();
      for (const Node& item : n.seq) j.push_back(treeJson(item));
      return j;
    }
  }
  return Json(nullptr);
}

}  // namespace

std::string resolvedRigJson(const std::string& yaml_text, const std::string& display_name,
                            const std::vector<std::string>& overrides, bool already_loaded) {
  Node root = checkedRigTree(yaml_text, RigSource{display_name, overrides});
  // a single rig is checked whole here (unless the caller did); a network (platforms:) by its
  // own loader, before
  if (!already_loaded && !root.find("platforms")) loadRigText(yaml_text, display_name, overrides);
  Json j = treeJson(root);
  if (!root.find("name")) {  // the name it ran under (yaml/rig_loader.h), first
    Json named = Json::object();
    named["name"] = rigStem(display_name);
    for (auto it = j.begin(); it != j.end(); ++it) named[it.key()] = *it;
    j = std::move(named);
  }
  return j.dump();
}

}  // namespace metrosync
