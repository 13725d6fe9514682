#include "contact/law_registry.h"

#include <algorithm>

namespace metrosync {

const std::vector<const LawKind*>& lawRegistry() {
#define METROSYNC_LIST_LAW(f) &f(),
  static const std::vector<const LawKind*> laws = {METROSYNC_FRICTION_LAWS(METROSYNC_LIST_LAW)};
#undef METROSYNC_LIST_LAW
  return laws;
}

namespace {
bool hasKey(const LawKind& kind, const std::string& key) {
  for (const LawParameter& p : kind.parameters())
    if (key == p.key) return true;
  return false;
}
void addOnce(std::vector<std::string>& list, const std::string& s) {
  if (std::find(list.begin(), list.end(), s) == list.end()) list.push_back(s);
}
}  // namespace

std::vector<std::string> lawNames() {
  std::vector<std::string> names;
  for (const LawKind* k : lawRegistry()) addOnce(names, k->name());
  return names;
}

std::string lawsWithKey(const std::string& key) {
  std::vector<std::string> names;
  for (const LawKind* k : lawRegistry())
    if (hasKey(*k, key)) addOnce(names, k->name());
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : " or ") + n;
  return out;
}

std::vector<std::string> lawKeys() {
  std::vector<std::string> keys;
  for (const LawKind* k : lawRegistry())
    for (const LawParameter& p : k->parameters()) addOnce(keys, p.key);
  return keys;
}

const LawKind* findLaw(const std::string& name, const std::vector<std::string>& keys) {
  for (const LawKind* k : lawRegistry()) {
    if (name != k->name()) continue;
    const auto given = [&](const LawParameter& p) {
      return p.fallback || std::find(keys.begin(), keys.end(), p.key) != keys.end();
    };
    if (std::all_of(keys.begin(), keys.end(),
                    [&](const std::string& key) { return hasKey(*k, key); }) &&
        std::all_of(k->parameters().begin(), k->parameters().end(), given))
      return k;
  }
  return nullptr;
}

}  // namespace metrosync
