// Internal to yaml/: the rig file's schema (which keys exist where, for each units) and the shape
// pass that checks a tree against it before any value is read.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "models/rig.h"
#include "yaml/rig_source.h"

namespace metrosync::rigfile {

struct Schema;
using SchemaPtr = std::shared_ptr<const Schema>;
struct Schema {
  enum class Kind { Number, Text, Bool, Map, List };
  Kind kind = Kind::Number;
  std::vector<std::pair<std::string, SchemaPtr>> keys;  // Map
  SchemaPtr item;                                       // List
  bool named = false;  // List: a key may name an element by its `name` (docs/keys.md)

  const Schema* key(const std::string& k) const {
    for (const auto& kv : keys)
      if (kv.first == k) return kv.second.get();
    return nullptr;
  }
};

const Schema& physicalSchema();
const Schema& scaledSchema();
const Schema& schemaOf(Units u);
const Schema& otherSchemaOf(Units u);
const char* otherUnits(Units u);
// The rig's units if its `units` key says physical or scaled.
std::optional<Units> unitsOf(const Node& root);

// What is wrong with `key` in a map of schema `here` at `parent` (as typed; `other`: the same
// place in the other units' schema, if any), in a rig of `units`: a key of the other units names
// the key to write instead (yaml/units_advice.h).
std::string unknownKeyMessage(const std::string& parent, const std::string& key, const Schema& here,
                              const Schema* other, Units units);

// Shape pass: unknown keys anywhere, and maps, lists and single values where they belong. Runs
// before any value is read, so that a typo is reported as a typo and not as a missing key.
void checkShape(const Node& n, const Schema& s, const Schema* other, Units units,
                const std::string& path, const Source& src);

}  // namespace metrosync::rigfile
