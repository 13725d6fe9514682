#include "yaml/rig_overrides.h"

#include "yaml/rig_reader.h"
#include "yaml/rig_schema.h"

namespace metrosync::rigfile {

namespace {

// Empty if `key` names a place in `s`, else what is wrong. A list takes an index, '*' (every
// element) or, in a named list, an element's name; indices and names are checked against the
// rig's tree afterwards (expandKey, yaml/key_path.h).
std::string schemaPathError(const Schema& s0, const Schema* other, Units units,
                            const KeyPath& key) {
  const Schema* s = &s0;
  for (std::size_t i = 0; i < key.size(); ++i) {
    const KeyPath::Segment& seg = key[i];
    const std::string here = printable(key.prefix(i + 1)), done = printable(key.prefix(i));
    if (s->kind == Schema::Kind::Map) {
      if (seg.kind == KeyPath::Segment::Kind::Every)
        return here + ": '*' stands for every element of a list, and " +
               (done.empty() ? std::string("the rig") : done) + " is a map of keys";
      const Schema* child = s->key(seg.text);
      if (!child) return here + ": " + unknownKeyMessage(done, seg.text, *s, other, units);
      s = child;
      other = other ? other->key(seg.text) : nullptr;
    } else if (s->kind == Schema::Kind::List) {
      if (seg.kind == KeyPath::Segment::Kind::Name && !s->named)
        return here + ": " + done + " is a list: expected an index from 0, or * for every element";
      s = s->item.get();
      other = other ? other->item.get() : nullptr;
    } else {
      return here + ": " + done + " is a single value, it has no key '" + printable(seg.text) + "'";
    }
  }
  return {};
}

}  // namespace

namespace {

// `key` (in the rig's own keys) checked against the schema and expanded on the tree.
std::vector<KeyPath> resolveOwnKey(const Node& root, const KeyPath& key, Units& units) {
  if (auto u = unitsOf(root)) {
    units = *u;
    const std::string err = schemaPathError(schemaOf(units), &otherSchemaOf(units), units, key);
    if (!err.empty()) throw KeyError(err);
  } else {
    const std::string err_p = schemaPathError(physicalSchema(), nullptr, Units::Physical, key);
    const std::string err_s = schemaPathError(scaledSchema(), nullptr, Units::Scaled, key);
    if (!err_p.empty() && !err_s.empty()) throw KeyError(err_p);
    units = err_p.empty() ? Units::Physical : Units::Scaled;
  }
  return expandKey(key, root);
}

}  // namespace

// The one resolver of keys (docs/keys.md); a single rig answers its platform's keys as a network
// of one does (platforms.0..., platforms.platform...)
std::vector<KeyPath> resolveIn(const Node& root, const KeyPath& typed, Units& units) {
  const KeyPath key = singlePlatformKey(typed, root);
  if (key == typed) return resolveOwnKey(root, key, units);
  try {
    return resolveOwnKey(root, key, units);
  } catch (const KeyError& e) {
    throw KeyError(printable(typed.text()) + " is " + printable(key.text()) +
                   " on this single-platform rig: " + e.what());
  }
}

namespace {

// The rig's other keys are written in its units: a --set cannot reinterpret them, and the errors
// that would follow would blame the file's keys rather than the --set.
void refuseUnitsSwitch(const Node& old_units, const Node& value, const Where& here,
                       const Source& src) {
  if (old_units.at.origin != 0 || old_units.kind != Node::Kind::Scalar) return;
  if (value.kind == Node::Kind::Scalar && value.scalar == old_units.scalar) return;
  src.fail(here, "the rig is written in units: " + shown(old_units) + " (line " +
                     std::to_string(old_units.at.line) +
                     "); a --set cannot change the units of its other keys (convert the rig: "
                     "'metrosync scale' prints its scaled parameters)");
}

// `value` at the concrete `path` (names and indices, from resolveIn), creating absent maps on
// the way (a valid key may be absent from the file).
void setAt(Node& root, const KeyPath& path, const Node& value, Units units, const Where& here,
           const Source& src) {
  const Schema* s = &schemaOf(units);
  Node* cur = &root;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const std::string& seg = path[i].text;
    const std::string at = path.prefix(i + 1), done = path.prefix(i);
    Node* next = nullptr;
    if (s->kind == Schema::Kind::Map) {
      if (cur->kind != Node::Kind::Map)
        src.fail(here, at + ": " + done + " is " + kindName(*cur) + " in the rig, not a map");
      s = s->key(seg);
      next = cur->find(seg);
      if (!next) {
        Node fresh;
        fresh.at = here;
        fresh.kind = s->kind == Schema::Kind::List ? Node::Kind::Seq : Node::Kind::Map;
        cur->map.push_back(Entry{seg, here, fresh});
        next = &cur->map.back().value;
      }
    } else {  // a list: resolveIn checked an index against this very tree
      // a name kept past the tree's end (a list the rig does not have, made just above)
      if (path[i].kind != KeyPath::Segment::Kind::Index || path[i].index >= cur->seq.size())
        src.fail(here, printable(at) + ": " + done + " has no entries (none is named '" +
                           printable(seg) + "')");
      s = s->item.get();
      next = &cur->seq[path[i].index];
    }
    cur = next;
  }
  if (path.text() == "units") refuseUnitsSwitch(*cur, value, here, src);
  *cur = value;
}

void applyOverride(Node& root, int origin, const Source& src) {
  const std::string& text = src.overrides()[origin - 1];
  const Where here{0, 0, origin};
  KeyAssignment set;
  try {
    set = parseAssignment(text);
  } catch (const KeyError& e) {
    src.fail(here, e.what());
  }
  const std::string& path = set.key.text();
  if (auto bad = firstBadUtf8(text))
    src.fail(here, "not UTF-8 text (byte " + std::to_string(*bad + 1) + " of the --set)");
  // the value, parsed as YAML so that numbers, names, maps and lists all work
  Node value;
  try {
    value = parseTree(set.value, origin);
  } catch (const TreeError& e) {
    src.fail(here, path + (e.syntax ? ": the value is not valid YAML (" + e.what + ")"
                                    : ": the value: " + e.what));
  }
  if (root.kind != Node::Kind::Map)
    src.fail(here, "the rig is " + std::string(kindName(root)) + ", not a map of keys");
  Units units = Units::Physical;
  std::vector<KeyPath> paths;
  try {
    paths = resolveIn(root, set.key, units);
  } catch (const KeyError& e) {
    src.fail(here, e.what());
  }
  // `*` sets every element, exactly as one --set per index would
  for (const KeyPath& p : paths) setAt(root, p, value, units, here, src);
}

}  // namespace

Node rootWithOverrides(const std::string& yaml_text, const Source& src) {
  Node root;
  try {
    root = parseTree(yaml_text, 0);
  } catch (const TreeError& e) {
    src.fail(e.at, (e.syntax ? "YAML syntax error: " : "") + e.what);
  }
  if (root.kind != Node::Kind::Map)
    src.fail(root.at, std::string("the rig is ") + kindName(root) +
                          "; expected a map of keys starting with units: physical or scaled");
  applyOverrides(root, src, 1);
  return root;
}

void applyOverrides(Node& root, const Source& src, std::size_t first) {
  for (std::size_t k = first; k <= src.overrides().size(); ++k)
    applyOverride(root, static_cast<int>(k), src);
}

}  // namespace metrosync::rigfile
