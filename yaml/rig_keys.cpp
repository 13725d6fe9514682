// The rig's keys as the command-line options ask them (yaml/rig_loader.h: rigNumber,
// resolveRigKey): resolved by the one key resolver (yaml/key_path.h) on the rig after --set.
#include "yaml/rig_loader.h"
#include "yaml/rig_overrides.h"
#include "yaml/rig_reader.h"

namespace metrosync {

using namespace rigfile;

std::optional<double> rigNumber(const std::string& yaml_text, const std::string& display_name,
                                const std::vector<std::string>& overrides, const std::string& key) {
  loadRigText(yaml_text, display_name, overrides);  // the rig must be valid
  const Source src(display_name, overrides);
  const Node root = rootWithOverrides(yaml_text, src);
  std::vector<KeyPath> paths;
  try {
    Units units = Units::Physical;
    paths = resolveIn(root, KeyPath::parse(key), units);
  } catch (const KeyError& e) {
    throw RigError(printable(display_name) + ": " + printable(key) + ": " + e.what());
  }
  const Node* n = &root;  // the first path: every segment a name or an index
  for (const KeyPath::Segment& seg : paths.front().segments()) {
    if (seg.kind == KeyPath::Segment::Kind::Index)
      n = n->kind == Node::Kind::Seq ? &n->seq.at(seg.index) : nullptr;
    else
      n = n->kind == Node::Kind::Map ? n->find(seg.text) : nullptr;
    if (!n) return std::nullopt;
  }
  if (n->kind != Node::Kind::Scalar || !parseNumber(n->scalar))
    throw RigError(display_name + ": " + paths.front().text() + " is not a number");
  return parseNumber(n->scalar);
}

RigKey resolveRigKey(const std::string& yaml_text, const std::string& display_name,
                     const std::vector<std::string>& sets, const std::string& key,
                     const std::string& typed) {
  const Source src(display_name, sets);
  const Node root = rootWithOverrides(yaml_text, src);
  RigKey k;
  try {
    k.key = KeyPath::parse(key);
    Units units = Units::Physical;
    k.paths = resolveIn(root, k.key, units);
  } catch (const KeyError& e) {
    throw RigError(printable(display_name) + ": " + printable(typed) + ": " + e.what());
  }
  return k;
}

}  // namespace metrosync
