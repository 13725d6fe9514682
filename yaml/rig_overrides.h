// Internal to yaml/: `--set key.path=value` overrides on a rig's tree, through the one resolver of
// keys (yaml/key_path.h, docs/keys.md).
#pragma once

#include <string>
#include <vector>

#include "models/rig.h"
#include "yaml/key_path.h"
#include "yaml/rig_source.h"

namespace metrosync::rigfile {

// The concrete paths `key` stands for in the tree `root`, checked against the schema of its
// units (either units' schema while they are unknown: `units` says which one fits). Throws
// KeyError.
std::vector<KeyPath> resolveIn(const Node& root, const KeyPath& key, Units& units);

// The rig's tree with src's overrides applied in order (not yet checked against the schema):
// text, one YAML document, bounded size and depth, no aliases (yaml/rig_tree.h).
Node rootWithOverrides(const std::string& yaml_text, const Source& src);
// src's overrides from the first-th (1-based) on, applied in order to a tree that has the ones
// before (rootWithOverrides is the text's tree and every override from the first).
void applyOverrides(Node& root, const Source& src, std::size_t first);

}  // namespace metrosync::rigfile
