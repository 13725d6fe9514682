// Rig files: YAML text -> a tree that remembers where each value was written -> --set overrides
// -> a shape pass against the schema (unknown keys, maps vs lists vs values) -> a build pass that
// reads, range-checks and converts every value into a Rig -> a plan pass on the built rig (the
// run's end, sample interval and estimated output, the integrator's name, starts below the top).
// Every limit on the way is in docs/rig-limits.md.
//
// Which keys are required (everything else is optional, with the default given):
//   both units:  units; platform.friction.law, with mu (coulomb) or c (viscous), nothing for
//                none/fixed; metronomes (a list of >= 1); simulation with duration (physical,
//                seconds) or tau (scaled, slow time). Optional: name (the file's stem),
//                start {x, v} (0, 0), simulation.{accuracy (1e-8), integrator (the engine's
//                default), sample (the engine's default)}.
//   physical:    gravity (9.81); platform.mass; platform.spring.k (no spring); per metronome:
//                box_mass (>= 0), pendulum.{mass, length, exactly one of damping | decay_rate
//                (write damping: 0 for an undamped pendulum), inertia (mass * length^2)},
//                escapement (none: impulse 0, theta_c 0) with angle and exactly one of
//                impulse | steady_amplitude, start.{angle, rate} (0, 0), locked (false; a locked
//                pendulum keeps its other keys, which the engines ignore).
//   scaled:      epsilon; per metronome nu, J, theta_c; alpha, zeta (0; and 0 by definition for
//                metronome 1); start either {A, phi} (both) or {theta, thetadot} (each 0).
// A metronome's name defaults to its 1-based number.
#include "yaml/rig_loader.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

#include "models/scaling.h"
#include "yaml/key_path.h"
#include "yaml/rig_build.h"
#include "yaml/rig_tree.h"
#include "yaml/utf8.h"

namespace metrosync {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Slack on inertia >= m L^2: inputs rounded to 4 significant digits (the SPEC's own example,
// 1.144e-5 against 0.0226 * 0.0225^2 = 1.1441e-5) must pass; a value in the slack is raised to
// m L^2, which is what it stands for.
constexpr double kInertiaSlack = 1e-3;

const char* kindName(const Node& n) {
  switch (n.kind) {
    case Node::Kind::Null:
      return "empty";
    case Node::Kind::Scalar:
      return "a single value";
    case Node::Kind::Map:
      return "a map";
    case Node::Kind::Seq:
      return "a list";
  }
  return "?";
}

// How a node is shown after "key = " in a message.
std::string shown(const Node& n) {
  switch (n.kind) {
    case Node::Kind::Null:
      return "(nothing)";
    case Node::Kind::Scalar: {
      if (n.scalar.empty()) return "''";
      if (n.scalar.size() > 40) return printable(n.scalar.substr(0, 37)) + "...";
      return printable(n.scalar);
    }
    case Node::Kind::Map:
      return "(a map)";
    case Node::Kind::Seq:
      return "(a list)";
  }
  return "?";
}

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

std::string joinPath(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

// Where messages point: the rig text (file:line:col) or the --set that wrote the node.
class Source {
 public:
  Source(std::string name, std::vector<std::string> overrides)
      : name_(std::move(name)), overrides_(std::move(overrides)) {}

  const std::string& name() const { return name_; }
  const std::vector<std::string>& overrides() const { return overrides_; }

  [[noreturn]] void fail(const Where& at, const std::string& what) const {
    std::ostringstream os;
    os << printable(name_);
    if (at.origin > 0)
      os << ": --set " << printable(overrides_[at.origin - 1]);
    else if (at.line > 0)
      os << ':' << at.line << ':' << at.col;
    os << ": " << what;
    throw RigError(os.str());
  }

 private:
  std::string name_;
  std::vector<std::string> overrides_;
};

// ---------------------------------------------------------------------------------------------
// the schema: which keys exist where, for each units

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

SchemaPtr frictionSchema() {
  return mapOf({{"law", text()}, {"mu", number()}, {"c", number()}});
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
                           {"decay_rate", number()}})},
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

// Optimal string alignment distance (Levenshtein plus adjacent transpositions), case-blind.
std::size_t editDistance(const std::string& a0, const std::string& b0) {
  std::string a = a0, b = b0;
  for (char& ch : a) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  for (char& ch : b) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

// The closest candidate if it is close enough to be a typo (or a prefix of at least 3 letters).
std::optional<std::string> closest(const std::string& word, const std::vector<std::string>& cands) {
  std::optional<std::string> best;
  std::size_t best_d = 0;
  for (const std::string& c : cands) {
    std::size_t d = editDistance(word, c);
    const std::size_t allowed = 1 + std::max(word.size(), c.size()) / 4;
    const bool prefix = word.size() >= 3 && c.compare(0, word.size(), word) == 0;
    if (d > allowed && !prefix) continue;
    if (prefix) d = std::min<std::size_t>(d, allowed);
    if (!best || d < best_d) best = c, best_d = d;
  }
  return best;
}

// What is wrong with `key` in a map of schema `here` (`other`: the same place in the other
// units' schema, if any).
std::string unknownKeyMessage(const std::string& key, const Schema& here, const Schema* other,
                              const char* other_units) {
  if (other && other->key(key)) return std::string("only with units: ") + other_units;
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

// Shape pass: unknown keys anywhere, and maps, lists and single values where they belong. Runs
// before any value is read, so that a typo is reported as a typo and not as a missing key.
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
                 child_path + value + ": " + unknownKeyMessage(e.key, s, other, otherUnits(units)));
      }
      checkShape(e.value, *child, other ? other->key(e.key) : nullptr, units, child_path, src);
    }
  }
  if (want_list)
    for (std::size_t i = 0; i < n.seq.size(); ++i)
      checkShape(n.seq[i], *s.item, other ? other->item.get() : nullptr, units,
                 joinPath(path, std::to_string(i)), src);
}

// ---------------------------------------------------------------------------------------------
// --set overrides

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
      if (!child) return here + ": " + unknownKeyMessage(seg.text, *s, other, otherUnits(units));
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

std::optional<Units> unitsOf(const Node& root) {
  const Node* u = root.kind == Node::Kind::Map ? root.find("units") : nullptr;
  if (u && u->kind == Node::Kind::Scalar && u->scalar == "physical") return Units::Physical;
  if (u && u->kind == Node::Kind::Scalar && u->scalar == "scaled") return Units::Scaled;
  return std::nullopt;
}

// The one resolver of keys (docs/keys.md): the concrete paths `key` stands for in the tree
// `root`, checked against the schema of its units (either units' schema while they are unknown:
// `units` says which one fits). Throws KeyError.
std::vector<KeyPath> resolveIn(const Node& root, const KeyPath& key, Units& units) {
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
    } else {  // a list: resolveIn checked the index against this very tree
      s = s->item.get();
      next = &cur->seq.at(path[i].index);
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

// ---------------------------------------------------------------------------------------------
// the build pass: read, range-check and convert values

std::optional<double> parseNumber(std::string s) {
  if (!s.empty() && s[0] == '+') s.erase(0, 1);
  std::string low = s;
  for (char& ch : low) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (low == ".inf") return HUGE_VAL;
  if (low == "-.inf") return -HUGE_VAL;
  if (low == ".nan") return std::nan("");
  double v = 0.0;
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(s.data(), end, v);
  if (s.empty() || ptr != end) return std::nullopt;
  // out of double's range: overflow is reported as not finite, underflow as the tiny value
  if (ec == std::errc::result_out_of_range) return std::strtod(s.c_str(), nullptr);
  if (ec != std::errc()) return std::nullopt;
  return v;
}

// A map being read: typed getters whose errors name the key, the value and where it was written.
class Reader {
 public:
  Reader(const Node& node, std::string path, const Source& src)
      : node_(&node), path_(std::move(path)), src_(&src) {}

  std::string path(const std::string& key) const { return joinPath(path_, key); }
  const std::string& path() const { return path_; }
  const Node* find(const std::string& key) const { return node_->find(key); }
  bool has(const std::string& key) const { return find(key) != nullptr; }
  const Where& at() const { return node_->at; }

  [[noreturn]] void missing(const std::string& key, const std::string& what) const {
    src_->fail(node_->at, path(key) + ": missing (" + what + ")");
  }
  [[noreturn]] void bad(const std::string& key, const std::string& why) const {
    const Node& n = *find(key);
    src_->fail(n.at, path(key) + " = " + shown(n) + ": " + why);
  }
  void forbid(const std::string& key, const std::string& why) const {
    if (has(key)) bad(key, why);
  }

  std::optional<double> optNumber(const std::string& key) const {
    const Node* n = find(key);
    if (!n) return std::nullopt;
    const std::optional<double> v = parseNumber(n->scalar);
    if (!v) bad(key, "must be a number");
    if (!std::isfinite(*v)) bad(key, "must be a finite number");
    return v;
  }
  double number(const std::string& key, const std::string& what) const {
    if (!has(key)) missing(key, what);
    return *optNumber(key);
  }
  std::optional<std::string> optText(const std::string& key) const {
    const Node* n = find(key);
    return n ? std::optional<std::string>(n->scalar) : std::nullopt;
  }
  std::string text(const std::string& key, const std::string& what) const {
    if (!has(key)) missing(key, what);
    return find(key)->scalar;
  }
  std::optional<bool> optBool(const std::string& key) const {
    const Node* n = find(key);
    if (!n) return std::nullopt;
    std::string low = n->scalar;
    for (char& ch : low) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (low == "true" || low == "yes" || low == "on") return true;
    if (low == "false" || low == "no" || low == "off") return false;
    bad(key, "must be true or false");
  }
  std::optional<Reader> optMap(const std::string& key) const {
    const Node* n = find(key);
    return n ? std::optional<Reader>(Reader(*n, path(key), *src_)) : std::nullopt;
  }
  Reader map(const std::string& key, const std::string& what) const {
    if (!has(key)) missing(key, what);
    return *optMap(key);
  }

 private:
  const Node* node_;
  std::string path_;
  const Source* src_;
};

// range checks: each returns the value, or fails naming key, value and rule
double positive(const Reader& r, const std::string& key, const std::string& what) {
  const double v = r.number(key, what);
  if (!(v > 0)) r.bad(key, "must be > 0");
  return v;
}
double nonNegative(const Reader& r, const std::string& key, double v) {
  if (!(v >= 0)) r.bad(key, "must be >= 0");
  return v;
}

// A name goes into files (summary.json, CSV headers) and, for the rig, an output folder.
std::optional<std::string> optName(const Reader& r) {
  const std::optional<std::string> name = r.optText("name");
  if (!name) return name;
  if (name->empty()) r.bad("name", "must not be empty");
  if (name->size() > kMaxNameBytes)
    r.bad("name", "is " + std::to_string(name->size()) + " bytes long (at most " +
                      std::to_string(kMaxNameBytes) + ")");
  if (firstControl(*name))  // C0, DEL and C1 (yaml/utf8.h)
    r.bad("name", "must not contain control characters");
  return name;
}

std::string readName(const Reader& top, const std::string& fallback) {
  const std::optional<std::string> name = optName(top);
  if (!name) return fallback;
  if (name->find_first_of("/\\") != std::string::npos)
    top.bad("name", "must not contain '/' or '\\' (it names the output folder)");
  return *name;
}

struct Friction {
  FrictionLaw law = FrictionLaw::Coulomb;
  double mu = 0.0, c = 0.0;
};

// platform.friction in either units (mu and c are scaled in a scaled rig)
Friction readFriction(const Reader& platform, Units units) {
  const bool scaled = units == Units::Scaled;
  const Reader f = platform.map(
      "friction", "e.g. friction: {law: coulomb, mu: " + std::string(scaled ? "0.4" : "6.5e-4") +
                      "}; law: coulomb, viscous, none or fixed");
  const std::string law = f.text("law", "coulomb, viscous, none or fixed");
  Friction out;
  if (law == "coulomb") {
    out.law = FrictionLaw::Coulomb;
    f.forbid("c", "only with law: viscous");
    out.mu = nonNegative(
        f, "mu",
        f.number("mu", scaled ? "the scaled Coulomb coefficient mu = mu-bar / epsilon^{3/2}"
                              : "mu-bar: |F| = mu-bar * M_total * g"));
  } else if (law == "viscous") {
    out.law = FrictionLaw::Viscous;
    f.forbid("mu", "only with law: coulomb");
    out.c = nonNegative(f, "c",
                        f.number("c", scaled ? "the scaled coefficient c = c-bar / (M omega0)"
                                             : "c-bar in N s/m: F = -c-bar xdot"));
  } else if (law == "none" || law == "fixed") {
    out.law = law == "none" ? FrictionLaw::None : FrictionLaw::Fixed;
    f.forbid("mu", "only with law: coulomb");
    f.forbid("c", "only with law: viscous");
  } else {
    std::string why = "must be coulomb, viscous, none or fixed";
    if (auto c = closest(law, {"coulomb", "viscous", "none", "fixed"}))
      why += " (did you mean '" + *c + "'?)";
    f.bad("law", why);
  }
  return out;
}

// start: {x, v}, both units
void readPlatformStart(const Reader& top, double& x, double& v) {
  if (auto s = top.optMap("start")) {
    x = s->optNumber("x").value_or(0.0);
    v = s->optNumber("v").value_or(0.0);
  }
}

// simulation: {duration | tau, accuracy, integrator, sample}
void readSimulation(const Reader& top, const char* duration_key, const std::string& what,
                    double& duration, double& accuracy, std::string& integrator, double& sample) {
  const Reader s = top.map("simulation", std::string("at least ") + duration_key);
  duration = positive(s, duration_key, what);
  if (auto a = s.optNumber("accuracy")) {
    if (!(*a > 0 && *a < 1)) s.bad("accuracy", "must be in (0, 1)");
    if (*a < kMinAccuracy)
      s.bad("accuracy",
            "must be >= " + fmt(kMinAccuracy) +
                ": no integrator can meet a smaller relative error in double precision");
    accuracy = *a;
  }
  if (auto name = s.optText("integrator")) integrator = *name;  // the engine checks the name
  if (auto dt = s.optNumber("sample")) {
    if (!(*dt > 0)) s.bad("sample", "must be > 0");
    sample = *dt;
  }
}

const Node& readMetronomeList(const Reader& top, const std::string& what) {
  if (!top.has("metronomes")) top.missing("metronomes", what);
  const Node& list = *top.find("metronomes");
  if (list.seq.empty()) top.bad("metronomes", "must hold at least one metronome");
  if (list.seq.size() > kMaxMetronomes)
    top.bad("metronomes", "holds " + std::to_string(list.seq.size()) + " metronomes (at most " +
                              std::to_string(kMaxMetronomes) + ", see docs/rig-limits.md)");
  return list;
}

// pendulum: mass, length, inertia (>= m L^2), damping or decay_rate (e1.1a)
void readPhysicalPendulum(const Reader& m, MetronomeSpec& mt) {
  const Reader p = m.map("pendulum", "mass, length and damping or decay_rate");
  mt.pendulum_mass_kg = positive(p, "mass", "kg");
  mt.length_m = positive(p, "length", "m, pivot to centre of mass");
  const double point_inertia = mt.pendulum_mass_kg * mt.length_m * mt.length_m;
  mt.inertia_kgm2 = point_inertia;
  if (auto I = p.optNumber("inertia")) {
    if (!(*I >= point_inertia * (1.0 - kInertiaSlack)))
      p.bad("inertia",
            "must be >= mass * length^2 = " + fmt(point_inertia) + " (parallel-axis theorem)");
    mt.inertia_kgm2 = std::max(*I, point_inertia);
  }
  const bool has_damping = p.has("damping"), has_decay = p.has("decay_rate");
  if (has_damping && has_decay) p.bad("decay_rate", "give damping or decay_rate, not both");
  if (!has_damping && !has_decay)
    p.missing("damping", "nu-bar in kg/s, or decay_rate in 1/s; damping: 0 for none");
  if (has_damping) {
    mt.damping_kg_s = nonNegative(p, "damping", *p.optNumber("damping"));
  } else {
    // theta-bar'' + (nu-bar L^2 / I) theta-bar' + ...: the amplitude decays at rate
    // nu-bar L^2 / (2 I) (paper s3, beta = nu-bar / 2m for I = m L^2)
    const double rate = nonNegative(p, "decay_rate", *p.optNumber("decay_rate"));
    mt.damping_kg_s = 2.0 * rate * mt.inertia_kgm2 / (mt.length_m * mt.length_m);
  }
}

// escapement: critical angle and impulse, or a steady amplitude that sets the impulse later
// (`amplitude` keeps its reader until the scaled parameters are known)
void readPhysicalEscapement(const Reader& m, MetronomeSpec& mt, std::optional<Reader>& amplitude) {
  if (auto e = m.optMap("escapement")) {
    mt.theta_c_rad = e->number("angle", "rad, the critical angle theta_c");
    if (!(mt.theta_c_rad > 0 && mt.theta_c_rad < kPi)) e->bad("angle", "must be in (0, pi)");
    const bool has_impulse = e->has("impulse"), has_amplitude = e->has("steady_amplitude");
    if (has_impulse && has_amplitude)
      e->bad("steady_amplitude", "give impulse or steady_amplitude, not both");
    if (!has_impulse && !has_amplitude)
      e->missing("impulse", "N m s per tick, or steady_amplitude in rad");
    if (has_impulse) {
      mt.impulse_Nms = nonNegative(*e, "impulse", *e->optNumber("impulse"));
    } else {
      // eq. A_star: A_star is the stable amplitude only if A_star >= sqrt(2) theta_c
      const double A = *e->optNumber("steady_amplitude");
      const double lowest = std::sqrt(2.0) * mt.theta_c_rad;
      if (!(A >= lowest && A < kPi))
        e->bad("steady_amplitude",
               "must be in [sqrt(2) * angle, pi) = [" + fmt(lowest) +
                   ", 3.14159) (below sqrt(2) * angle no impulse makes it the stable amplitude)");
      if (!(mt.damping_kg_s > 0))
        e->bad("steady_amplitude",
               "needs damping > 0 (an undamped pendulum has no steady amplitude)");
      amplitude = *e;
    }
  }
}

// steady_amplitude -> J by eq. J_estimate with the metronome's own scaled nu_i, theta_c,i,
// then J-bar_i = eps J_i I_i sqrt(eps) omega0
void impulsesFromSteadyAmplitudes(Rig& rig,
                                  const std::vector<std::optional<Reader>>& amplitude_of) {
  const ScaledParams sp = computeScaled(rig);
  for (std::size_t i = 0; i < rig.metronomes.size(); ++i) {
    if (!amplitude_of[i]) continue;
    const Reader& e = *amplitude_of[i];
    const double A = *e.optNumber("steady_amplitude") / sp.angle_scale;
    double J = 0.0;
    try {
      J = impulseForAmplitude(sp.nu[i], A, sp.theta_c[i]);
    } catch (const std::invalid_argument& err) {
      e.bad("steady_amplitude", err.what());
    }
    MetronomeSpec& mt = rig.metronomes[i];
    mt.impulse_Nms = sp.epsilon * sp.angle_scale * J * mt.inertia_kgm2 / sp.time_scale_s;
  }
}

// platform_path and metronomes_path name the platform and its metronomes in messages: "platform"
// and "metronomes" in a single-platform rig, "platforms.I" and "platforms.I.metronomes" for a
// platform of a network (whose tree is given in the single-platform form, see buildNetworkRig).
Rig buildPhysical(const Node& root, const Source& src, const std::string& fallback_name,
                  const std::string& platform_path = "platform",
                  const std::string& metronomes_path = "metronomes") {
  const Reader top(root, "", src);
  Rig rig;
  rig.units = Units::Physical;
  rig.name = readName(top, fallback_name);
  if (auto g = top.optNumber("gravity")) {
    if (!(*g > 0)) top.bad("gravity", "must be > 0");
    rig.gravity_m_s2 = *g;
  }

  // platform
  if (!top.has("platform")) top.missing("platform", "the board's mass and its friction law");
  const Reader platform(*top.find("platform"), platform_path, src);
  rig.platform.mass_kg = positive(platform, "mass", "the board's mass in kg");
  const Friction fr = readFriction(platform, Units::Physical);
  rig.platform.law = fr.law;
  rig.platform.mu_bar = fr.mu;
  rig.platform.c_Ns_m = fr.c;
  if (auto spring = platform.optMap("spring"))
    rig.platform.spring_N_m = nonNegative(*spring, "k", spring->number("k", "N/m"));
  readPlatformStart(top, rig.platform.start_x_m, rig.platform.start_v_m_s);

  // metronomes; a steady_amplitude becomes an impulse once the scaled parameters are known
  const Node& list = readMetronomeList(top, "a list of metronomes, each with box_mass, pendulum");
  std::vector<std::optional<Reader>> amplitude_of(list.seq.size());
  for (std::size_t i = 0; i < list.seq.size(); ++i) {
    const Reader m(list.seq[i], metronomes_path + "." + std::to_string(i), src);
    MetronomeSpec mt;
    mt.name = optName(m).value_or(std::to_string(i + 1));
    // a mass, > 0 (SPEC 1c): a massless box would leave its pendulum's pivot without inertia
    mt.box_mass_kg = positive(m, "box_mass", "kg, the metronome without its pendulum");

    readPhysicalPendulum(m, mt);
    readPhysicalEscapement(m, mt, amplitude_of[i]);

    if (auto s = m.optMap("start")) {
      mt.start_angle_rad = s->optNumber("angle").value_or(0.0);
      mt.start_rate_rad_s = s->optNumber("rate").value_or(0.0);
    }
    mt.locked = m.optBool("locked").value_or(false);
    rig.metronomes.push_back(mt);
  }

  readSimulation(top, "duration", "s", rig.sim.t_end_s, rig.sim.accuracy, rig.sim.integrator,
                 rig.sim.sample_s);

  impulsesFromSteadyAmplitudes(rig, amplitude_of);
  return rig;
}

Rig buildScaled(const Node& root, const Source& src, const std::string& fallback_name) {
  const Reader top(root, "", src);
  ScaledRigInput in;
  in.name = readName(top, fallback_name);
  in.epsilon = top.number("epsilon", "the small parameter m1^2 L1^2 / (I1 M), in (0, 1)");
  if (!(in.epsilon > 0 && in.epsilon < 1)) top.bad("epsilon", "must be in (0, 1)");
  const double eps = in.epsilon;

  const Reader platform = top.map("platform", "its friction law");
  const Friction fr = readFriction(platform, Units::Scaled);
  in.law = fr.law;
  in.mu = fr.mu;
  in.c = fr.c;
  readPlatformStart(top, in.x0, in.xdot0);

  const Node& list = readMetronomeList(top, "a list of metronomes, each with nu, J, theta_c");
  // the escapement angle theta-bar_c = sqrt(eps) theta_c must be a physical angle in (0, pi)
  const double theta_c_max = kPi / std::sqrt(eps);
  for (std::size_t i = 0; i < list.seq.size(); ++i) {
    const Reader m(list.seq[i], "metronomes." + std::to_string(i), src);
    ScaledMetronomeInput mt;
    mt.name = optName(m).value_or(std::to_string(i + 1));
    mt.nu = nonNegative(m, "nu", m.number("nu", "scaled pendulum damping, >= 0"));
    mt.J = nonNegative(m, "J", m.number("J", "scaled escapement impulse, >= 0"));
    mt.theta_c = m.number("theta_c", "scaled critical angle of the escapement");
    if (!(mt.theta_c > 0 && mt.theta_c < theta_c_max))
      m.bad("theta_c", "must be in (0, pi / sqrt(epsilon)) = (0, " + fmt(theta_c_max) +
                           ") (the angle sqrt(epsilon) theta_c must be in (0, pi))");
    for (const char* key : {"alpha", "zeta"}) {
      const std::optional<double> v = m.optNumber(key);
      if (!v) continue;
      if (i == 0 && *v != 0.0)
        m.bad(key, "must be 0: metronome 1 is the reference (alpha and zeta are 0 by definition)");
      // 1 + eps alpha = (its frequency / metronome 1's)^2 and 1 + eps zeta = m L / (m1 L1)
      if (!(1.0 + eps * *v > 0))
        m.bad(key, "must be > -1 / epsilon = " + fmt(-1.0 / eps) + " (1 + epsilon " + key +
                       " must be > 0)");
      (std::string(key) == "alpha" ? mt.alpha : mt.zeta) = *v;
    }
    if (auto s = m.optMap("start")) {
      const bool polar = s->has("A") || s->has("phi");
      if (polar) {
        for (const char* key : {"theta", "thetadot"})
          s->forbid(key, "give start as {A, phi} or as {theta, thetadot}, not both");
        const double A = s->number("A", "scaled amplitude, with phi");
        if (!(A >= 0)) s->bad("A", "must be >= 0");
        const double phi = s->number("phi", "phase in rad, with A");
        mt.theta0 = A * std::sin(phi);  // theta = A sin phi, thetadot = A cos phi
        mt.thetadot0 = A * std::cos(phi);
      } else {
        mt.theta0 = s->optNumber("theta").value_or(0.0);
        mt.thetadot0 = s->optNumber("thetadot").value_or(0.0);
      }
    }
    in.metronomes.push_back(mt);
  }

  readSimulation(top, "tau", "slow time; the fast time runs to t = tau / epsilon", in.tau_end,
                 in.accuracy, in.integrator, in.sample);

  try {
    return rigFromScaled(in);
  } catch (const std::invalid_argument& err) {
    top.bad("epsilon", err.what());
  }
}

// What a run of the rig would write, against the caller's limit (yaml/rig_limits.h); blamed on
// simulation.sample if given, else on the run's length.
void checkOutput(const Reader& sim, const char* duration_key, const Rig& rig,
                 const LoadOptions& opt) {
  const char* culprit = sim.has("sample") ? "sample" : duration_key;
  if (!std::isfinite(rig.sim.t_end_s))
    sim.bad(duration_key, "the run would end at t = " + fmt(rig.sim.t_end_s) +
                              " s: it must end at a finite time");
  if (rig.sim.sample_s > 0 && rig.sim.sample_s < rig.sim.t_end_s * kSampleResolution)
    sim.bad("sample", "below the time resolution of the run (" + fmt(kSampleResolution) +
                          " * its length, " + fmt(rig.sim.t_end_s * kSampleResolution) +
                          " s here): consecutive rows would have the same time");
  const OutputEstimate e = estimateOutput(rig);
  if (e.periods > kMaxRunPeriods)  // every command: the cost of the run itself (issue 29)
    sim.bad(duration_key,
            "the run would span " + fmt(e.periods) + " fast periods" +
                (rig.units == Units::Scaled ? " (the fast time runs to tau / epsilon)" : "") +
                ", above the limit of " + fmt(kMaxRunPeriods) +
                " for any command (docs/rig-limits.md): shorten the run");
  if (!(e.bytes > opt.max_output_bytes)) return;
  sim.bad(culprit, "the run would write about " + fmt(e.trajectory_rows) +
                       " trajectory rows (every " + fmt(e.sample_s) + " s) and " +
                       fmt(e.envelope_rows) + " envelope rows, about " + fmt(e.bytes) +
                       " bytes, above the output limit of " + fmt(opt.max_output_bytes) +
                       " bytes: raise simulation.sample, shorten the run, or lift the limit with "
                       "--max-output BYTES");
}

// Where a start is blamed: the --set that changed one of its values if any, else the start map.
Where startCulprit(const Reader& metronome) {
  const Node* start = metronome.find("start");
  if (!start) return metronome.at();
  for (const Entry& e : start->map)
    if (e.value.at.origin > 0) return e.value.at;
  return start->at;
}

// Checks that need the built rig's derived values, each blamed on the key that asked for them.
void checkPlan(const Node& root, const Rig& rig, const Source& src, const LoadOptions& opt) {
  const Reader top(root, "", src);
  const Reader sim = top.map("simulation", "");
  const char* duration_key = rig.units == Units::Physical ? "duration" : "tau";
  if (auto name = sim.optText("integrator"); name && !opt.integrators.empty()) {
    const auto& names = opt.integrators;
    if (std::find(names.begin(), names.end(), *name) == names.end()) {
      std::string why = "unknown integrator";
      if (auto c = closest(*name, names)) why += " (did you mean '" + *c + "'?)";
      sim.bad("integrator", why + "; " + opt.integrator_help);
    }
  }
  checkOutput(sim, duration_key, rig, opt);
  const Node& list = *top.find("metronomes");
  for (std::size_t i = 0; i < rig.metronomes.size() && i < list.seq.size(); ++i) {
    const std::optional<std::string> why = overTheTop(rig.metronomes[i], rig.gravity_m_s2);
    if (!why) continue;
    const Reader m(list.seq[i], "metronomes." + std::to_string(i), src);
    src.fail(startCulprit(m), m.path("start") + ": " + *why);
  }
}

std::string stemOf(const std::string& display_name) {
  std::string stem = std::filesystem::path(display_name).stem().string();
  return stem.empty() ? std::string("rig") : stem;
}

// The rig's tree with the overrides applied (not yet checked against the schema): text, one
// YAML document, bounded size and depth, no aliases (yaml/rig_tree.h).
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
  for (std::size_t k = 1; k <= src.overrides().size(); ++k)
    applyOverride(root, static_cast<int>(k), src);
  return root;
}

}  // namespace

Rig loadRigText(const std::string& yaml_text, const std::string& display_name,
                const std::vector<std::string>& overrides, const LoadOptions& options) {
  const Source src(display_name, overrides);
  const Node root = checkedRigTree(yaml_text, RigSource{display_name, overrides});
  const std::optional<Units> units = unitsOf(root);  // checked: units decide the schema
  const std::string stem = stemOf(display_name);
  if (const Node* couplings = root.find("couplings"); couplings && !root.find("platforms"))
    src.fail(couplings->at,
             "couplings: join the platforms of a network (platforms: [...], docs/networks.md); "
             "this rig has one platform, with nothing to couple it to");
  if (const Node* platforms = root.find("platforms")) {
    // a network (docs/networks.md): one platform on the table, uncoupled, is today's rig
    const Network net = buildNetwork(root, RigSource{display_name, overrides}, stem, options);
    if (net.isSingleRig()) return net.toSingleRig();
    src.fail(platforms->at, "platforms: a network of " + std::to_string(net.platforms.size()) +
                                " platforms and " + std::to_string(net.couplings.size()) +
                                " coupling(s); this command takes a single platform (a network "
                                "runs with `metrosync run --engine direct`, see docs/networks.md)");
  }
  const Rig rig =
      *units == Units::Physical ? buildPhysical(root, src, stem) : buildScaled(root, src, stem);
  try {
    checkPlan(root, rig, src, options);
  } catch (const std::invalid_argument& e) {  // computeScaled on a rig it cannot scale
    src.fail(Where{}, e.what());
  }
  return rig;
}

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

namespace {

void appendJsonString(std::string& out, const std::string& s) {
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

void appendJson(std::string& out, const Node& n) {
  switch (n.kind) {
    case Node::Kind::Null:
      out += "null";
      return;
    case Node::Kind::Scalar: {
      const std::optional<double> v = parseNumber(n.scalar);
      if (v && std::isfinite(*v)) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.17g", *v);
        out += buf;
      } else {
        appendJsonString(out, n.scalar);
      }
      return;
    }
    case Node::Kind::Map:
      out += '{';
      for (std::size_t k = 0; k < n.map.size(); ++k) {
        if (k) out += ", ";
        appendJsonString(out, n.map[k].key);
        out += ": ";
        appendJson(out, n.map[k].value);
      }
      out += '}';
      return;
    case Node::Kind::Seq:
      out += '[';
      for (std::size_t k = 0; k < n.seq.size(); ++k) {
        if (k) out += ", ";
        appendJson(out, n.seq[k]);
      }
      out += ']';
      return;
  }
}

}  // namespace

std::string resolvedRigJson(const std::string& yaml_text, const std::string& display_name,
                            const std::vector<std::string>& overrides, bool already_loaded) {
  Node root = checkedRigTree(yaml_text, RigSource{display_name, overrides});
  // a single rig is checked whole here (unless the caller did); a network (platforms:) by its
  // own loader, before
  if (!already_loaded && !root.find("platforms")) loadRigText(yaml_text, display_name, overrides);
  if (!root.find("name")) {
    Entry name;
    name.key = "name";
    name.value.kind = Node::Kind::Scalar;
    name.value.scalar = stemOf(display_name);  // the name it ran under (yaml/rig_loader.h)
    root.map.insert(root.map.begin(), std::move(name));
  }
  std::string out;
  appendJson(out, root);
  return out;
}

Node checkedRigTree(const std::string& yaml_text, const RigSource& rs) {
  const Source src(rs.display_name, rs.overrides);
  const Node root = rootWithOverrides(yaml_text, src);
  const Reader top(root, "", src);
  if (!top.has("units")) top.missing("units", "physical or scaled");
  const std::optional<Units> units = unitsOf(root);
  if (!units) top.bad("units", "must be physical or scaled");
  checkShape(root, schemaOf(*units), &otherSchemaOf(*units), *units, "", src);
  return root;
}

std::string rigStem(const std::string& display_name) {
  return stemOf(display_name);
}

void failAt(const RigSource& src, const Where& at, const std::string& what) {
  Source(src.display_name, src.overrides).fail(at, what);
}

std::optional<double> parseRigNumber(const std::string& scalar) {
  return parseNumber(scalar);
}

Rig buildNetworkPlatformRig(const Node& root, const RigSource& rs, const std::string& fallback_name,
                            const std::string& platform_path, const LoadOptions& options) {
  const Source src(rs.display_name, rs.overrides);
  const Rig rig =
      buildPhysical(root, src, fallback_name, platform_path, platform_path + ".metronomes");
  try {
    checkPlan(root, rig, src, options);
  } catch (const std::invalid_argument& e) {  // computeScaled on a rig it cannot scale
    src.fail(root.at, platform_path + ": " + e.what());
  }
  return rig;
}

Rig loadRigFile(const std::string& path, const std::vector<std::string>& overrides,
                const LoadOptions& options) {
  return loadRigText(readRigFile(path), path, overrides, options);
}

std::string defaultRigYaml() {
  // keep byte for byte equal to yaml/rigs/experiment.yaml (tests/yaml checks it)
  return R"(# The paper's experiment (section 3): two Wittner Super-Mini Ruby metronomes, adjustable weight
# removed, on a platform on large PVC rollers on a smooth table (the lowest friction measured),
# started near antiphase. The built-in default rig of `metrosync run` and `metrosync compare`.
units: physical
name: experiment
gravity: 9.81
platform:
  mass: 0.1432                  # kg, the board alone: M = 0.3088 kg with both metronomes
  friction: {law: coulomb, mu: 6.5e-4}
metronomes:
  - name: A
    box_mass: 0.0602            # kg, 82.8 g with its pendulum
    pendulum:
      mass: 0.0226              # kg; inertia defaults to mass * length^2
      length: 0.0225            # m, pivot to the fixed weight
      decay_rate: 0.5           # 1/s, measured below the escapement angle on a still table
    escapement:
      angle: 0.244              # rad (14 deg)
      steady_amplitude: 0.785   # rad (45 deg), alone on a still table
    start: {angle: 0.785, rate: 0.0}
  - name: B
    box_mass: 0.0602
    pendulum:
      mass: 0.0226
      length: 0.0225
      decay_rate: 0.5
    escapement:
      angle: 0.244
      steady_amplitude: 0.785
    start: {angle: -0.785, rate: 0.25}
simulation:
  duration: 200                 # s
)";
}

Rig defaultRig(const std::vector<std::string>& overrides, const LoadOptions& options) {
  return loadRigText(defaultRigYaml(), "<default rig>", overrides, options);
}

}  // namespace metrosync
