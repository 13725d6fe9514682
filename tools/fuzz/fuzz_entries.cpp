#include "tools/fuzz/fuzz_entries.h"

#include <cmath>
#include <regex>

#include "sim/analysis/basin.h"
#include "sim/analysis/fit/data_file.h"
#include "sim/analysis/sweep.h"
#include "tools/cli/sweep.h"
#include "tools/fuzz/command_line_parser.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"
#include "yaml/utf8.h"

namespace metrosync::fuzz {

namespace {

const char* const kRigName = "fuzz.yaml";

// A network of two platforms, one metronome each: the keys' second tree (platform names, a
// metronome list per platform).
const char* const kNetworkYaml = R"(units: physical
name: fuzz-network
platforms:
  - name: left
    mass: 1.0
    friction: {law: viscous, c: 0.05}
    spring: {k: 55.0, c: 0.0}
    metronomes:
      - {box_mass: 0.1, pendulum: {mass: 0.02, length: 0.05, inertia: 1.16e-4, decay_rate: 0.3}, escapement: {angle: 0.2, steady_amplitude: 0.5}, start: {angle: 0.1}}
  - name: right
    mass: 1.0
    friction: {law: coulomb, mu: 0.01}
    metronomes:
      - {box_mass: 0.1, pendulum: {mass: 0.02, length: 0.05, inertia: 1.16e-4, decay_rate: 0.3}, escapement: {angle: 0.2, steady_amplitude: 0.5}, start: {angle: -0.1}}
couplings:
  - {between: [left, right], k: 5.0}
simulation: {duration: 1}
)";

[[noreturn]] void finding(const std::string& what, const std::string& message) {
  throw FuzzFinding(what + ": " + message.substr(0, 400));
}

// "<name>:<line>:<col>: ..." or "<name>: --set ...": the rig loader's located message.
void expectLocated(const std::string& message, const std::string& name) {
  static const std::regex where(R"(^:[0-9]+:[0-9]+: |^: --set )");
  if (message.rfind(name, 0) != 0 || !std::regex_search(message.substr(name.size()), where))
    finding("a rig error without its place", message);
}

// A loaded rig keeps the loader's promises: finite, positive masses, at least one metronome.
void checkRig(const Rig& rig) {
  if (rig.metronomes.empty()) finding("a rig loaded without metronomes", rig.name);
  for (const MetronomeSpec& m : rig.metronomes)
    if (!(std::isfinite(m.pendulum_mass_kg) && m.pendulum_mass_kg > 0.0 &&
          std::isfinite(m.length_m) && std::isfinite(m.inertia_kgm2) &&
          std::isfinite(m.start_angle_rad) && std::isfinite(m.start_rate_rad_s)))
      finding("a metronome loaded with a non-finite or non-positive number", rig.name);
}

}  // namespace

std::vector<std::string> nulSeparated(std::string_view input) {
  std::vector<std::string> parts(1);
  for (char c : input) {
    if (c == '\0')
      parts.emplace_back();
    else
      parts.back() += c;
  }
  return parts;
}

void rigLoader(std::string_view input) {
  std::vector<std::string> parts = nulSeparated(input);
  const std::string text = parts.front();
  parts.erase(parts.begin());
  try {
    checkRig(loadRigText(text, kRigName, parts));
    resolvedRigJson(text, kRigName, parts, true);
  } catch (const RigError& e) {
    expectLocated(e.what(), kRigName);
  }
}

void networkLoader(std::string_view input) {
  std::vector<std::string> parts = nulSeparated(input);
  const std::string text = parts.front();
  parts.erase(parts.begin());
  try {
    const Network net = loadNetworkText(text, kRigName, parts);
    if (net.platforms.empty()) finding("a network loaded without platforms", text);
    loadPlatformsNetwork(text, kRigName, parts);
  } catch (const RigError& e) {
    expectLocated(e.what(), kRigName);
  }
}

namespace {

// The key as a --vary of `rig_text`: refused with the --set words after the option as typed
// (control characters escaped).
void resolveAsVary(const std::string& rig_text, const std::string& key) {
  const std::string typed = "--vary " + key + "=0:1:2";
  try {
    const RigKey k = resolveRigKey(rig_text, kRigName, {}, key, typed);
    if (k.paths.empty()) finding("a key that stands for no rig key", key);
  } catch (const RigError& e) {
    const std::string m = e.what();
    if (m.rfind(std::string(kRigName) + ": " + printable(typed), 0) != 0)
      finding("a --vary key's error without the option as typed", m);
  }
}

}  // namespace

void keyPath(std::string_view input) {
  const std::string text(input);
  try {
    const KeyPath k = KeyPath::parse(text);
    if (k.size() == 0 || KeyPath::parse(k.text()) != k)
      finding("a key that parses twice apart", text);
    resolveAsVary(defaultRigYaml(), k.text());
    resolveAsVary(kNetworkYaml, k.text());
  } catch (const KeyError&) {
  }
  try {
    loadRigText(defaultRigYaml(), kRigName, {text});
  } catch (const RigError& e) {
    expectLocated(e.what(), kRigName);
  }
  try {
    loadNetworkText(kNetworkYaml, kRigName, {text});
  } catch (const RigError& e) {
    expectLocated(e.what(), kRigName);
  }
}

void dataFile(std::string_view input) {
  for (int n : {0, 2}) {
    try {
      const MeasuredData d = parseDataText(std::string(input), "fuzz.csv", n);
      for (size_t k = 0; k < d.t_s.size(); ++k)
        if (!std::isfinite(d.t_s[k]) || (k > 0 && !(d.t_s[k] > d.t_s[k - 1])))
          finding("a data file read with times not finite and increasing", std::string(input));
      for (const DataColumn& c : d.columns) {
        if (c.values.size() != d.t_s.size()) finding("a column of another length", c.name);
        for (double v : c.values)
          if (std::isinf(v)) finding("an infinite sample read", c.name);
      }
    } catch (const DataError& e) {
      if (std::string(e.what()).rfind("fuzz.csv", 0) != 0)
        finding("a data error without the file's name", e.what());
    }
  }
}

namespace {

// A sweep's grid as the command checks it before any rig: the axes, the grid (lifted to the hard
// cap: it must still be described, not listed), the manifest's text, the maps' axes, the shard.
void checkSweepOptions(const cli::SweepOptions& o) {
  try {
    std::vector<SweepAxis> axes;
    for (const auto& v : o.vary) axes.push_back(parseVary(v));
    const SweepGrid grid(std::move(axes), kMaxForcedGridPoints);
    // (the command refuses a key that is not UTF-8 when it resolves it against the rig, before
    // sweep.json: here bytes that are not UTF-8 are replaced, so that the size is measured)
    const std::string manifest =
        grid.toJson().dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    if (manifest.size() > (std::size_t(1) << 20) + 64 * o.vary.size() * 1024)
      finding("a sweep.json grid that grows with the grid", std::to_string(grid.size()));
    mapAxes(grid, o.map);
    if (!o.shard.empty()) parseShard(o.shard);
    for (const auto& r : o.random) parseRandom(r, false);
  } catch (const SweepInputError&) {
  }
}

}  // namespace

void options(std::string_view input) {
  std::vector<std::string> args = nulSeparated(input);
  if (args.size() > 64) args.resize(64);
  static CommandLineParser cl;  // built once
  cl.reset();
  if (!cl.parse(args).empty()) return;  // refused: CLI11's message or the number rule's
  if (cl.sweeps.sweep->parsed()) checkSweepOptions(cl.sweep);
  if (cl.basin_app->parsed()) {
    for (const auto& r : cl.basin.random) {
      try {
        parseRandom(r, true);
      } catch (const SweepInputError&) {
      }
    }
  }
}

const std::vector<Target>& targets() {
  static const std::vector<Target> t = {{"rig", rigLoader},
                                        {"network", networkLoader},
                                        {"keys", keyPath},
                                        {"data", dataFile},
                                        {"options", options}};
  return t;
}

}  // namespace metrosync::fuzz
