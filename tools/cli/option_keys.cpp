#include "tools/cli/option_keys.h"

#include "tools/cli/commands.h"
#include "yaml/utf8.h"

namespace metrosync::cli {

OptionKey resolveOptionKey(const KeyedRig& rig, const std::string& option, const std::string& value,
                           bool assignment) {
  OptionKey k;
  k.typed = option + " " + value;
  k.key = resolveRigKey(rig.text, rig.display_name, rig.sets, assignment ? keyTextOf(value) : value,
                        k.typed);
  return k;
}

void refuseSharedKeys(const std::vector<OptionKey>& keys) {
  for (std::size_t a = 0; a < keys.size(); ++a)
    for (std::size_t b = a + 1; b < keys.size(); ++b) {
      const std::string shared = sharedPath(keys[a].key.paths, keys[b].key.paths);
      if (shared.empty()) continue;
      const KeyPath& key = keys[a].key.key;
      throw UsageError(
          printable(keys[a].typed + " and " + keys[b].typed +
                    (key == keys[b].key.key ? ": the key " + key.text() + " is given twice"
                                            : ": both set " + shared)));
    }
}

}  // namespace metrosync::cli
