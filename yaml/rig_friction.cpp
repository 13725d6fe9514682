// platform.friction: the law a rig file names, read through the registry of laws
// (contact/law_registry.h). The name and the keys written choose the law ({law: coulomb, mu} is
// Coulomb's law, {law: coulomb, mu, mu_static} static friction above kinetic); every parameter is
// required unless the law gives it a default, and >= 0; then the law's own rules (mu_static >=
// mu).
#include <algorithm>
#include <string>
#include <vector>

#include "contact/law_registry.h"
#include "yaml/rig_values.h"
#include "yaml/spelling.h"

namespace metrosync::rigfile {

namespace {

// "coulomb, viscous, none or fixed"
std::string namesText() {
  const std::vector<std::string> names = lawNames();
  std::string out;
  for (std::size_t k = 0; k < names.size(); ++k)
    out += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  return out;
}

bool has(const LawKind& kind, const std::string& key) {
  const std::vector<LawParameter>& ps = kind.parameters();
  return std::any_of(ps.begin(), ps.end(), [&](const LawParameter& p) { return key == p.key; });
}

// The smallest law named `name` that has every key in `keys` (nullptr if none).
const LawKind* smallestWith(const std::string& name, const std::vector<std::string>& keys) {
  const LawKind* best = nullptr;
  for (const LawKind* k : lawRegistry()) {
    if (name != k->name()) continue;
    if (!std::all_of(keys.begin(), keys.end(),
                     [&](const std::string& key) { return has(*k, key); }))
      continue;
    if (!best || k->parameters().size() < best->parameters().size()) best = k;
  }
  return best;
}

const char* help(const LawParameter& p, Units units) {
  return units == Units::Scaled ? p.scaled_help : p.physical_help;
}

// The law the name and the written keys choose; fails on a key no law of that name takes, or
// on a key missing for the smallest law that takes them all.
const LawKind& chooseLaw(const Reader& f, const std::string& name, Units units) {
  std::vector<std::string> keys;
  for (const Entry& e : f.node().map)
    if (e.key != "law") keys.push_back(e.key);
  if (const LawKind* exact = findLaw(name, keys)) return *exact;
  for (const std::string& key : keys)
    if (!smallestWith(name, {key})) f.bad(key, "only with law: " + lawsWithKey(key));
  const LawKind* want = smallestWith(name, keys);
  if (!want) f.bad(keys.back(), "no law: " + name + " takes all of these keys together");
  for (const LawParameter& p : want->parameters())
    if (!f.has(p.key) && !p.fallback) f.missing(p.key, help(p, units));
  return *want;  // not reached: findLaw would have matched
}

}  // namespace

FrictionLaw readFriction(const Reader& platform, Units units) {
  const bool scaled = units == Units::Scaled;
  const std::string names = namesText();
  const Reader f = platform.map(
      "friction", "e.g. friction: {law: coulomb, mu: " + std::string(scaled ? "0.4" : "6.5e-4") +
                      "}; law: " + names);
  const std::string name = f.text("law", names);
  const std::vector<std::string> known = lawNames();
  if (std::find(known.begin(), known.end(), name) == known.end()) {
    std::string why = "must be " + names;
    if (auto c = closest(name, known)) why += " (did you mean '" + *c + "'?)";
    f.bad("law", why);
  }
  const LawKind& kind = chooseLaw(f, name, units);
  std::vector<double> values;
  for (const LawParameter& p : kind.parameters())
    values.push_back(!f.has(p.key) && p.fallback
                         ? *p.fallback
                         : nonNegative(f, p.key, f.number(p.key, help(p, units))));
  const FrictionLaw law(kind, values);
  if (const std::optional<LawViolation> v = law.violation()) f.bad(v->key, v->why);
  return law;
}

}  // namespace metrosync::rigfile
