// A rig loaded once and built again at other values of some keys (yaml/rig_loader.h).
//
// Why at() equals loadRigText with the keys' overrides appended: loadRigText parses the text,
// applies the overrides in order (rootWithOverrides), checks the tree (units, the keys' places and
// kinds: checkedRigTree) and builds the rig from it (rigFromCheckedTree). The tree before the
// keys' overrides does not depend on their values, so it is made once; the keys' overrides are
// then applied to a copy exactly as loadRigText applies them. The checks of the tree look at the
// kinds of the nodes (map, list, single value) and at `units`, never at another value's text, and
// a number is always a single value: so they pass for every number when they pass for one (the
// probe below), and are not repeated. Anything else -- a probe that fails, a key on `units`, a
// value that is not finite -- takes loadRigText itself.
#include <cmath>

#include "base/number_text.h"
#include "yaml/rig_build.h"
#include "yaml/rig_loader.h"
#include "yaml/rig_overrides.h"

namespace metrosync {

using namespace rigfile;

struct RigAtValues::Tree {
  Node root;  // the text's tree with the rig's own overrides applied
};

RigAtValues::RigAtValues(std::string yaml_text, std::string display_name,
                         std::vector<std::string> overrides, std::vector<std::string> keys,
                         LoadOptions options)
    : text_(std::move(yaml_text)),
      display_name_(std::move(display_name)),
      overrides_(std::move(overrides)),
      keys_(std::move(keys)),
      options_(std::move(options)) {
  for (const std::string& k : keys_)
    if (k == "units") return;  // its value decides the checks
  try {
    checkedRigTree(text_,
                   RigSource{display_name_, withValues(std::vector<double>(keys_.size(), 1.0))});
    auto tree = std::make_shared<Tree>();
    tree->root = rootWithOverrides(text_, Source(display_name_, overrides_));
    tree_ = std::move(tree);
  } catch (const RigError&) {
    tree_ = nullptr;  // at() gives loadRigText's own message
  }
}

RigAtValues::~RigAtValues() = default;

std::vector<std::string> RigAtValues::withValues(const std::vector<double>& values) const {
  std::vector<std::string> o = overrides_;
  for (std::size_t k = 0; k < keys_.size(); ++k)
    o.push_back(keys_[k] + "=" + roundTripText(values.at(k)));
  return o;
}

Rig RigAtValues::at(const std::vector<double>& values) const {
  const std::vector<std::string> all = withValues(values);
  bool finite = true;
  for (double v : values) finite = finite && std::isfinite(v);
  if (!tree_ || !finite) return loadRigText(text_, display_name_, all, options_);
  Node root = tree_->root;
  applyOverrides(root, Source(display_name_, all), overrides_.size() + 1);
  return rigFromCheckedTree(root, RigSource{display_name_, all}, options_);
}

}  // namespace metrosync
