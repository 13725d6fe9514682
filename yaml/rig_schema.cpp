#include "yaml/rig_schema.h"

#include <initializer_list>

#include "contact/law_registry.h"
#include "yaml/spelling.h"
#include "yaml/units_advice.h"

namespace metrosync::rigfile {

namespace {

SchemaPtr leaf(Schema::Kind kind) {
  auto s = std::make_shared<Schema>();
  s->kind = kind;
  return s;
}
SchemaPtr number() {
  return leaf(Schema::Kind::Number);
}
SchemaPtr text() {
  return leaf(Schema::Kind::Text);
}
SchemaPtr boolean() {
  return leaf(Schema::Kind::Bool);
}
SchemaPtr mapOf(std::initializer_list<std::pair<std::string, SchemaPtr>> keys) {
  auto s = std::make_shared<Schema>();
  s->kind = Schema::Kind::Map;
  s->keys = keys;
  return s;
}
SchemaPtr listOf(SchemaPtr item, bool named = false) {
  auto s = std::make_shared<Schema>();
  s->kind = Schema::Kind::List;
  s->item = std::move(item);
  s->named = named;
  return s;
}

// platform.friction: law, and every parameter key of every law (contact/law_registry.h)
SchemaPtr frictionSchema() {
  auto s = std::make_shared<Schema>();
  s->kind = Schema::Kind::Map;
  s->keys.push_back({"law", text()});
  for (const std::string& key : lawKeys()) s->keys.push_back({key, number()});
  return s;
}
SchemaPtr simulationSchema(const char* duration_key) {
  return mapOf({{duration_key, number()},
                {"accuracy", number()},
                {"integrator", text()},
                {"sample", number()}});
}

SchemaPtr physicalMetronomeSchema() {
  return mapOf(
      {{"name", text()},
       {"box_mass", number()},
       {"pendulum", mapOf({{"mass", number()},
                           {"length", number()},
                           {"inertia", number()},
                           {"damping", number()},
                           {"decay_rate", number()},
                           {"air_drag", number()}})},
       {"escapement",
        mapOf({{"angle", number()}, {"impulse", number()}, {"steady_amplitude", number()}})},
       {"start", mapOf({{"angle", number()}, {"rate", number()}})},
       {"locked", boolean()}});
}
SchemaPtr platformStartSchema() {
  return mapOf({{"x", number()}, {"v", number()}});
}

// A network of platforms (docs/networks.md): `platforms` and `couplings` instead of `platform`,
// `metronomes` and `start`; physical units only.
SchemaPtr networkPlatformSchema() {
  return mapOf({{"name", text()},
                {"mass", number()},
                {"friction", frictionSchema()},
                {"spring", mapOf({{"k", number()}, {"c", number()}})},
                {"on", text()},
                {"metronomes", listOf(physicalMetronomeSchema())},
                {"start", platformStartSchema()}});
}
SchemaPtr couplingSchema() {
  return mapOf({{"between", listOf(text())}, {"k", number()}, {"c", number()}});
}

}  // namespace

const Schema& physicalSchema() {
  static const SchemaPtr s = mapOf({{"units", text()},
                                    {"name", text()},
                                    {"gravity", number()},
                                    {"platform", mapOf({{"mass", number()},
                                                        {"friction", frictionSchema()},
                                                        {"spring", mapOf({{"k", number()}})}})},
                                    {"metronomes", listOf(physicalMetronomeSchema())},
                                    {"start", platformStartSchema()},
                                    {"platforms", listOf(networkPlatformSchema(), true)},
                                    {"couplings", listOf(couplingSchema())},
                                    {"simulation", simulationSchema("duration")}});
  return *s;
}

const Schema& scaledSchema() {
  static const SchemaPtr s =
      mapOf({{"units", text()},
             {"name", text()},
             {"epsilon", number()},
             {"platform", mapOf({{"friction", frictionSchema()}})},
             {"metronomes", listOf(mapOf({{"name", text()},
                                          {"nu", number()},
                                          {"J", number()},
                                          {"theta_c", number()},
                                          {"alpha", number()},
                                          {"zeta", number()},
                                          {"start", mapOf({{"A", number()},
                                                           {"phi", number()},
                                                           {"theta", number()},
                                                           {"thetadot", number()}})}}))},
             {"start", mapOf({{"x", number()}, {"v", number()}})},
             {"simulation", simulationSchema("tau")}});
  return *s;
}

namespace {
const char* expected(const Schema& s) {
  switch (s.kind) {
    case Schema::Kind::Number:
      return "a number";
    case Schema::Kind::Text:
      return "a name";
    case Schema::Kind::Bool:
      return "true or false";
    case Schema::Kind::Map:
      return "a map of keys";
    case Schema::Kind::List:
      return "a list (lines starting with '- ')";
  }
  return "?";
}
}  // namespace

std::optional<Units> unitsOf(const Node& root) {
  const Node* u = root.kind == Node::Kind::Map ? root.find("units") : nullptr;
  if (u && u->kind == Node::Kind::Scalar && u->scalar == "physical") return Units::Physical;
  if (u && u->kind == Node::Kind::Scalar && u->scalar == "scaled") return Units::Scaled;
  return std::nullopt;
}

std::string unknownKeyMessage(const std::string& parent, const std::string& key, const Schema& here,
                              const Schema* other, Units units) {
  if (other && other->key(key)) {
    const std::string advice = otherUnitsAdvice(parent, key, units);
    return std::string("only with units: ") + otherUnits(units) +
           (advice.empty() ? "" : " (" + advice + ")");
  }
  std::vector<std::string> names;
  for (const auto& kv : here.keys) names.push_back(kv.first);
  if (auto c = closest(key, names)) return "unknown key (did you mean '" + *c + "'?)";
  // a key written one level too high, e.g. metronomes.0.mass for metronomes.0.pendulum.mass
  for (const auto& kv : here.keys)
    if (kv.second->kind == Schema::Kind::Map && kv.second->key(key))
      return "unknown key here (did you mean '" + kv.first + "." + key + "'?)";
  std::string all;
  for (const std::string& k : names) all += (all.empty() ? "" : ", ") + k;
  return "unknown key (expected one of: " + all + ")";
}

const char* otherUnits(Units u) {
  return u == Units::Physical ? "scaled" : "physical";
}
const Schema& schemaOf(Units u) {
  return u == Units::Physical ? physicalSchema() : scaledSchema();
}
const Schema& otherSchemaOf(Units u) {
  return u == Units::Physical ? scaledSchema() : physicalSchema();
}

void checkShape(const Node& n, const Schema& s, const Schema* other, Units units,
                const std::string& path, const Source& src) {
  const bool want_map = s.kind == Schema::Kind::Map, want_list = s.kind == Schema::Kind::List;
  const bool ok = want_map    ? n.kind == Node::Kind::Map
                  : want_list ? n.kind == Node::Kind::Seq
                              : n.kind == Node::Kind::Scalar;
  if (!ok) {
    if (n.kind == Node::Kind::Null)
      src.fail(n.at, path + ": has no value (expected " + expected(s) + ")");
    src.fail(n.at, path + " = " + shown(n) + ": must be " + expected(s) + ", not " + kindName(n));
  }
  if (want_map) {
    for (const Entry& e : n.map) {
      const Schema* child = s.key(e.key);
      const std::string child_path = joinPath(path, e.key);
      if (!child) {
        const std::string value =
            e.value.kind == Node::Kind::Scalar ? " = " + shown(e.value) : std::string();
        src.fail(e.key_at,
                 child_path + value + ": " + unknownKeyMessage(path, e.key, s, other, units));
      }
      checkShape(e.value, *child, other ? other->key(e.key) : nullptr, units, child_path, src);
    }
  }
  if (want_list)
    for (std::size_t i = 0; i < n.seq.size(); ++i)
      checkShape(n.seq[i], *s.item, other ? other->item.get() : nullptr, units,
                 joinPath(path, std::to_string(i)), src);
}

}  // namespace metrosync::rigfile
