// Networks of platforms (docs/networks.md, issue 13): rig files with `platforms:` and
// `couplings:` instead of `platform:` and `metronomes:`, physical units. Same messages, limits and
// --set overrides as single-platform rigs (yaml/rig_loader.h); a rig in today's form loads as a
// network of one platform named "platform".
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "models/network.h"
#include "yaml/rig_loader.h"

namespace metrosync {

// Does this rig text describe a network (a `platforms` key at the top)? Never throws: a text that
// does not parse is "not a network" (loading it then reports what is wrong).
bool isNetworkText(const std::string& yaml_text);

// Loads a network, or a single-platform rig as a network of one. Throws RigError (file, key,
// line and what is wrong) for every bad input: an unknown platform in a coupling or in `on`, a
// platform coupled to itself, duplicate names, a negative k or c, a cycle of `on`, couplings in a
// network whose platforms are all fixed, scaled units.
Network loadNetworkText(const std::string& yaml_text, const std::string& display_name,
                        const std::vector<std::string>& overrides = {},
                        const LoadOptions& options = {});
Network loadNetworkFile(const std::string& path, const std::vector<std::string>& overrides = {},
                        const LoadOptions& options = {});

// The rig text as a network that is not a single rig (Network::isSingleRig: one platform on the
// table, uncoupled, runs as today's rig); nullopt for a single-platform rig or a network of one.
// Every command that runs a rig asks this first. Throws RigError as loadNetworkText.
std::optional<Network> loadPlatformsNetwork(const std::string& yaml_text,
                                            const std::string& display_name,
                                            const std::vector<std::string>& overrides = {},
                                            const LoadOptions& options = {});

}  // namespace metrosync
