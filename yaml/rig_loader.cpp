// Rig files: YAML text -> a tree that remembers where each value was written -> --set overrides
// -> a shape pass against the schema (unknown keys, maps vs lists vs values) -> a build pass that
// reads, range-checks and converts every value into a Rig -> a plan pass on the built rig (the
// run's end, sample interval and estimated output, the integrator's name, starts below the top).
// Every limit on the way is in docs/rig-limits.md.
//
// Which keys are required (everything else is optional, with the default given):
//   both units:  units; platform.friction.law with its law's keys (contact/law_registry.h:
//                mu, or mu and mu_static, for coulomb; c for viscous; nothing for none/fixed,
//                yaml/rig_friction.cpp); metronomes (a list of >= 1); simulation with duration
//                (physical, seconds) or tau (scaled, slow time). Optional: name (the file's stem),
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
//
// The passes live in their own files: yaml/rig_tree (text -> tree), yaml/rig_overrides (--set),
// yaml/rig_schema (shape), yaml/rig_reader, yaml/rig_values and yaml/rig_friction (build),
// yaml/rig_plan (plan), with yaml/rig_source (where messages point) and yaml/spelling (did you
// mean); yaml/rig_json (resolved_rig), yaml/default_rig (the built-in rig). This file joins them.
#include "yaml/rig_loader.h"

#include <optional>
#include <stdexcept>

#include "models/network_text.h"
#include "yaml/rig_build.h"
#include "yaml/rig_overrides.h"
#include "yaml/rig_plan.h"
#include "yaml/rig_reader.h"
#include "yaml/rig_schema.h"
#include "yaml/rig_values.h"

namespace metrosync {

using namespace rigfile;

Rig loadRigText(const std::string& yaml_text, const std::string& display_name,
                const std::vector<std::string>& overrides, const LoadOptions& options) {
  const RigSource rs{display_name, overrides};
  return rigFromCheckedTree(checkedRigTree(yaml_text, rs), rs, options);
}

Rig rigFromCheckedTree(const Node& root, const RigSource& rs, const LoadOptions& options) {
  const std::string& display_name = rs.display_name;
  const std::vector<std::string>& overrides = rs.overrides;
  const Source src(display_name, overrides);
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
    src.fail(platforms->at, "platforms: a " + networkOfPlatforms(net.platforms.size()) + " and " +
                                std::to_string(net.couplings.size()) +
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

}  // namespace metrosync
