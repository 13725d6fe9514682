#include "yaml/network_loader.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "yaml/rig_build.h"
#include "yaml/utf8.h"

namespace metrosync {

namespace {

std::string at(const std::string& path, const std::string& key) {
  return path + "." + key;
}

// A number under `key` of the map n (nullopt if absent), finite and >= 0.
std::optional<double> nonNegativeAt(const Node& n, const std::string& key, const std::string& path,
                                    const RigSource& src) {
  const Node* v = n.find(key);
  if (!v) return std::nullopt;
  const std::optional<double> x = parseRigNumber(v->scalar);
  if (!x || !std::isfinite(*x))
    failAt(src, v->at, at(path, key) + " = " + v->scalar + ": must be a finite number");
  if (!(*x >= 0)) failAt(src, v->at, at(path, key) + " = " + v->scalar + ": must be >= 0");
  return x;
}

// The platform's tree in the single-platform form, every node where the file wrote it.
Node singleForm(const Node& root, const Node& platform) {
  Node out;
  out.kind = Node::Kind::Map;
  out.at = platform.at;
  auto copy = [&](const Node& from, const char* key, const char* as) {
    for (const Entry& e : from.map)
      if (e.key == key) out.map.push_back(Entry{as, e.key_at, e.value});
  };
  for (const char* key : {"units", "name", "gravity", "simulation"}) copy(root, key, key);
  out.map.push_back(Entry{"platform", platform.at, platform});
  copy(platform, "metronomes", "metronomes");
  copy(platform, "start", "start");
  return out;
}

// The platform's name: required, unique, usable in a CSV header (x_NAME) and a JSON key.
std::string platformName(const Node& p, const std::string& path, const RigSource& src,
                         const std::map<std::string, int>& seen) {
  const Node* n = p.find("name");
  if (!n) failAt(src, p.at, path + ".name: missing (every platform of a network has a name)");
  const std::string& name = n->scalar;
  if (name.empty() || name.size() > kMaxNameBytes)
    failAt(src, n->at, path + ".name: must be 1 to " + std::to_string(kMaxNameBytes) + " bytes");
  if (firstControl(name) || name.find_first_of(" ,\"") != std::string::npos)
    failAt(src, n->at,
           path + ".name = " + printable(name) +
               ": must not contain spaces, commas, quotes or control characters "
               "(it names CSV columns)");
  if (auto it = seen.find(name); it != seen.end())
    failAt(src, n->at,
           path + ".name = " + name + ": duplicate: platforms." + std::to_string(it->second) +
               " has the same name");
  return name;
}

// The index of the platform named by the scalar node n, or a message naming the known ones.
int platformIndex(const Node& n, const std::string& path, const RigSource& src,
                  const std::map<std::string, int>& names) {
  const auto it = names.find(n.scalar);
  if (it != names.end()) return it->second;
  std::string known;
  for (const auto& kv : names) known += (known.empty() ? "" : ", ") + kv.first;
  failAt(src, n.at,
         path + " = " + n.scalar + ": no platform has this name (platforms: " + known + ")");
}

// `on`: the platform below, no cycle; a platform on another is neither fixed nor sprung to the
// ground (its friction acts on the relative motion).
void resolveOn(Network& net, const Node& list, const RigSource& src,
               const std::map<std::string, int>& names) {
  const int n = static_cast<int>(net.platforms.size());
  for (int i = 0; i < n; ++i) {
    const Node* on = list.seq[i].find("on");
    if (!on) continue;
    const std::string path = "platforms." + std::to_string(i) + ".on";
    net.platforms[i].on = platformIndex(*on, path, src, names);
    if (net.platforms[i].on == i)
      failAt(src, on->at, path + " = " + on->scalar + ": a platform cannot rest on itself");
    const PlatformSpec& ps = net.platforms[i].rig.platform;
    if (!ps.friction.platformMoves())
      failAt(src, on->at,
             path + " = " + on->scalar +
                 ": a platform resting on another cannot be fixed to it (give its metronomes to "
                 "the one below)");
    if (ps.spring_N_m > 0 || net.platforms[i].spring_c_Ns_m > 0)
      failAt(src, on->at,
             path + " = " + on->scalar +
                 ": a platform resting on another has no spring to the ground");
  }
  for (int i = 0; i < n; ++i) {
    int p = i, depth = 0;
    for (int step = 0; step < n && p >= 0; ++step, ++depth) p = net.platforms[p].on;
    if (p >= 0)
      failAt(src, list.seq[i].find("on")->at,
             "platforms." + std::to_string(i) +
                 ".on: a cycle of `on` (platforms rest on each other in a ring)");
    if (depth > kMaxStackDepth)  // platform i and the `depth - 1` below it
      failAt(src, list.seq[i].find("on")->at,
             "platforms." + std::to_string(i) + ".on: a stack of " + std::to_string(depth) +
                 " platforms, one on another (at most " + std::to_string(kMaxStackDepth) +
                 ", see docs/rig-limits.md)");
  }
}

// A network whose every metronome is locked, refused at the `locked` that locked the last one: a
// --set's when one wrote any (the culprit the user typed), else the file's last.
[[noreturn]] void refuseAllLocked(const Node& list, const RigSource& src) {
  const Node* culprit = nullptr;
  std::string path = "platforms";
  for (std::size_t i = 0; i < list.seq.size(); ++i) {
    const Node* metronomes = list.seq[i].find("metronomes");
    for (std::size_t m = 0; metronomes && m < metronomes->seq.size(); ++m) {
      const Node* locked = metronomes->seq[m].find("locked");
      if (!locked || (culprit && culprit->at.origin > 0 && locked->at.origin == 0)) continue;
      culprit = locked;
      path = "platforms." + std::to_string(i) + ".metronomes." + std::to_string(m) +
             ".locked = " + printable(locked->scalar);
    }
  }
  failAt(src, culprit ? culprit->at : list.at,
         path +
             ": every metronome of the network is locked: nothing swings to simulate "
             "(unlock one: locked: false)");
}

// Every platform's metronomes together within kMaxMetronomes (the engines couple them all), and
// in a network of several platforms at least one of them swinging.
void checkNetworkSize(const Network& net, const Node& list, const RigSource& src) {
  std::size_t total = 0, swinging = 0;
  for (std::size_t i = 0; i < net.platforms.size(); ++i) {
    for (const MetronomeSpec& m : net.platforms[i].rig.metronomes) swinging += !m.locked;
    total += net.platforms[i].rig.metronomes.size();
    if (total > kMaxMetronomes)
      failAt(src, list.seq[i].at,
             "platforms." + std::to_string(i) + ": brings the network to " + std::to_string(total) +
                 " metronomes (at most " + std::to_string(kMaxMetronomes) +
                 " over all platforms, see docs/rig-limits.md)");
  }
  // one platform with its metronomes locked is today's rig, a board on its springs (section 3A);
  // a network of several needs a swinging pendulum for its time scale
  if (swinging == 0 && net.platforms.size() > 1) refuseAllLocked(list, src);
}

void readCouplings(Network& net, const Node& root, const RigSource& src,
                   const std::map<std::string, int>& names) {
  const Node* list = root.find("couplings");
  if (!list) return;
  for (std::size_t i = 0; i < list->seq.size(); ++i) {
    const Node& c = list->seq[i];
    const std::string path = "couplings." + std::to_string(i);
    const Node* between = c.find("between");
    if (!between || between->seq.size() != 2)
      failAt(src, between ? between->at : c.at,
             path + ".between: must name two platforms, e.g. between: [left, right]");
    Coupling k;
    k.a = platformIndex(between->seq[0], path + ".between.0", src, names);
    k.b = platformIndex(between->seq[1], path + ".between.1", src, names);
    if (k.a == k.b)
      failAt(src, between->at,
             path + ".between: couples platform " + between->seq[0].scalar + " to itself");
    const std::optional<double> kk = nonNegativeAt(c, "k", path, src);
    if (!kk)
      failAt(src, c.at, path + ".k: missing (the spring constant in N/m; 0 for a damper alone)");
    k.k_N_m = *kk;
    k.c_Ns_m = nonNegativeAt(c, "c", path, src).value_or(0.0);
    net.couplings.push_back(k);
  }
  const bool all_fixed = std::all_of(
      net.platforms.begin(), net.platforms.end(),
      [](const NetworkPlatform& p) { return !p.rig.platform.friction.platformMoves(); });
  if (all_fixed && !net.couplings.empty())
    failAt(src, list->at,
           "couplings: every platform is fixed, so the couplings join nothing that moves");
}

}  // namespace

Network buildNetwork(const Node& root, const RigSource& src, const std::string& fallback_name,
                     const LoadOptions& options) {
  for (const char* key : {"platform", "metronomes", "start"})
    if (const Node* n = root.find(key))
      failAt(src, n->at,
             std::string(key) +
                 ": give platforms (a network) or platform and metronomes (one platform), not "
                 "both; a network's platforms hold their own metronomes and start");
  const Node& list = *root.find("platforms");
  if (list.seq.empty()) failAt(src, list.at, "platforms: must hold at least one platform");
  if (list.seq.size() > kMaxPlatforms)
    failAt(src, list.at,
           "platforms: " + std::to_string(list.seq.size()) + " platforms (at most " +
               std::to_string(kMaxPlatforms) + ", see docs/rig-limits.md)");
  Network net;
  std::map<std::string, int> names;
  for (std::size_t i = 0; i < list.seq.size(); ++i) {
    const std::string path = "platforms." + std::to_string(i);
    NetworkPlatform p;
    p.name = platformName(list.seq[i], path, src, names);
    names[p.name] = static_cast<int>(i);
    p.rig =
        buildNetworkPlatformRig(singleForm(root, list.seq[i]), src, fallback_name, path, options);
    if (const Node* spring = list.seq[i].find("spring"))
      p.spring_c_Ns_m = nonNegativeAt(*spring, "c", path + ".spring", src).value_or(0.0);
    net.platforms.push_back(p);
  }
  net.name = net.platforms[0].rig.name;
  net.gravity_m_s2 = net.platforms[0].rig.gravity_m_s2;
  net.sim = net.platforms[0].rig.sim;
  checkNetworkSize(net, list, src);
  resolveOn(net, list, src, names);
  readCouplings(net, root, src, names);
  return net;
}

bool isNetworkText(const std::string& yaml_text) {
  // a text that never spells the key is no network: no parse (every run asks this first)
  if (yaml_text.find("platforms") == std::string::npos) return false;
  try {
    const Node root = parseTree(yaml_text, 0);
    return root.kind == Node::Kind::Map && root.find("platforms") != nullptr;
  } catch (const TreeError&) {
    return false;
  }
}

Network loadNetworkText(const std::string& yaml_text, const std::string& display_name,
                        const std::vector<std::string>& overrides, const LoadOptions& options) {
  const RigSource src{display_name, overrides};
  const Node root = checkedRigTree(yaml_text, src);
  if (root.find("platforms")) {
    if (root.find("units")->scalar != "physical")
      failAt(src, root.find("units")->at,
             "units: a network of platforms is written in physical units");
    return buildNetwork(root, src, rigStem(display_name), options);
  }
  // today's form: a network of one platform, exactly the rig
  Network net;
  NetworkPlatform p;
  p.name = kSinglePlatformName;  // what platforms.NAME... answers to (yaml/key_path.h)
  p.rig = loadRigText(yaml_text, display_name, overrides, options);
  net.name = p.rig.name;
  net.gravity_m_s2 = p.rig.gravity_m_s2;
  net.sim = p.rig.sim;
  net.platforms.push_back(p);
  return net;
}

Network loadNetworkFile(const std::string& path, const std::vector<std::string>& overrides,
                        const LoadOptions& options) {
  return loadNetworkText(readRigFile(path), path, overrides, options);
}

std::optional<Network> loadPlatformsNetwork(const std::string& yaml_text,
                                            const std::string& display_name,
                                            const std::vector<std::string>& overrides,
                                            const LoadOptions& options) {
  if (!isNetworkText(yaml_text)) return std::nullopt;
  Network net = loadNetworkText(yaml_text, display_name, overrides, options);
  if (net.isSingleRig()) return std::nullopt;
  return net;
}

}  // namespace metrosync
