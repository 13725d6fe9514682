// The rig keys a command's options name (--vary, --random, --param, --fold, --free), resolved
// against the rig before anything runs by the one resolver of keys (yaml/key_path.h,
// docs/keys.md): a bad key is refused with the same words whichever option typed it, and two
// options that set one rig key are refused. (--set goes through the rig loader itself.)
#pragma once

#include <string>
#include <vector>

#include "yaml/rig_loader.h"

namespace metrosync::cli {

// The rig the keys are resolved against: its text, the name messages give it, its --set.
struct KeyedRig {
  const std::string& text;
  const std::string& display_name;
  const std::vector<std::string>& sets;
};

// One option's key: what the user typed, for messages ("--vary metronomes.*.nu=0.5:0.8:4"),
// and the key resolved.
struct OptionKey {
  std::string typed;
  RigKey key;
};

// The key of `option VALUE` resolved against `rig`: VALUE is "KEY=..." when `assignment`
// (--vary, --random: the key is what precedes the first '='), else KEY alone (--param, --fold,
// --free). Throws RigError "<rig>: <option> <value>: <what is wrong with the key>".
OptionKey resolveOptionKey(const KeyedRig& rig, const std::string& option, const std::string& value,
                           bool assignment);

// Throws UsageError when two of `keys` set one rig key, naming both as typed and the key, e.g.
//   --vary metronomes.*.nu=0.5:0.8:4 and --vary metronomes.1.nu=0.6,0.7: both set metronomes.1.nu
void refuseSharedKeys(const std::vector<OptionKey>& keys);

}  // namespace metrosync::cli
