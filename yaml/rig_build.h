// Internal to yaml/: the pieces of the rig loader (yaml/rig_loader.cpp) that the network loader
// (yaml/network_loader.cpp) reuses, so that a network's messages are located exactly like a
// single-platform rig's (file:line:col or --set, key path, value, what is wrong).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "models/network.h"
#include "models/rig.h"
#include "yaml/load_options.h"
#include "yaml/rig_error.h"
#include "yaml/rig_tree.h"

namespace metrosync {

// Where a rig came from: its display name and its --set overrides (for the messages).
struct RigSource {
  std::string display_name;
  std::vector<std::string> overrides;
};

// The rig's tree after the overrides, its units and its keys checked (unknown keys, maps, lists
// and single values where they belong); no value read yet.
Node checkedRigTree(const std::string& yaml_text, const RigSource& src);
// The rig of a tree checkedRigTree gave (with the same src): every value read, range-checked and
// built, the plan checked (loadRigText is the two in turn).
Rig rigFromCheckedTree(const Node& root, const RigSource& src, const LoadOptions& options);
// The rig's name when it has no `name` key: the file's stem.
std::string rigStem(const std::string& display_name);

// Throws RigError "NAME:LINE:COL: what" (or "NAME: --set K=V: what" for a node a --set wrote).
[[noreturn]] void failAt(const RigSource& src, const Where& at, const std::string& what);
// A YAML scalar as a number (.inf, .nan and a leading + included); nullopt if it is not one.
std::optional<double> parseRigNumber(const std::string& scalar);

// One platform of a network in the single-platform form (units, name, gravity, platform,
// metronomes, start, simulation), built and checked as a single-platform rig would be; the
// messages name the platform as `platform_path` and its metronomes under it.
Rig buildNetworkPlatformRig(const Node& root, const RigSource& src,
                            const std::string& fallback_name, const std::string& platform_path,
                            const LoadOptions& options);

// The network of a checked tree holding `platforms` (yaml/network_loader.cpp).
Network buildNetwork(const Node& root, const RigSource& src, const std::string& fallback_name,
                     const LoadOptions& options);

}  // namespace metrosync
