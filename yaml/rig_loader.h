// Rig files (SPEC section 1): YAML in either units, `--set key.path=value` overrides (the keys of
// yaml/key_path.h), validation with file:line:col messages, and the built-in default rig. The only
// public face of yaml/; no yaml-cpp type crosses it.
#pragma once

#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/rig.h"
#include "yaml/key_path.h"
#include "yaml/load_options.h"
#include "yaml/rig_error.h"
#include "yaml/rig_limits.h"

namespace metrosync {

// Reads a rig file, applies the overrides in order ("key.path=value", the value parsed as YAML),
// validates everything and converts it to a Rig (a scaled rig becomes its equivalent physical
// system, see rigFromScaled). rig.name is the `name` key, else the file's stem. The path must be a
// regular file of at most kMaxRigFileBytes.
Rig loadRigFile(const std::string& path, const std::vector<std::string>& overrides = {},
                const LoadOptions& options = {});

// The text of a rig file, after checking the path: a regular file (not a directory, device, FIFO
// or socket) of at most kMaxRigFileBytes. Throws RigError naming the path and what is wrong.
std::string readRigFile(const std::string& path);

// The same for YAML text; display_name stands for the file in messages (and gives the name).
Rig loadRigText(const std::string& yaml_text, const std::string& display_name,
                const std::vector<std::string>& overrides = {}, const LoadOptions& options = {});

// A rig loaded once, then again with keys set to numbers (a continuation's parameter, tried at
// thousands of values): at(values) is loadRigText(yaml_text, display_name, overrides + {keys[k] +
// "=" + roundTripText(values[k])}) -- the same Rig or the same RigError -- without parsing the
// text and checking its keys again (yaml/rig_at_values.cpp says why that is exact). const and
// safe to call from several threads at once.
class RigAtValues {
 public:
  RigAtValues(std::string yaml_text, std::string display_name, std::vector<std::string> overrides,
              std::vector<std::string> keys, LoadOptions options = {});
  ~RigAtValues();
  Rig at(const std::vector<double>& values) const;

 private:
  struct Tree;
  std::vector<std::string> withValues(const std::vector<double>& values) const;
  std::string text_, display_name_;
  std::vector<std::string> overrides_, keys_;
  LoadOptions options_;
  std::shared_ptr<const Tree> tree_;  // null: at() loads the text each time
};

// The number at `key` (docs/keys.md; a key with '*': its first element) in the rig after the
// overrides, e.g. for the value a continuation starts from; nullopt when the key is absent (its
// default applies). Throws RigError for an invalid rig or key, or a value that is not a number.
std::optional<double> rigNumber(const std::string& yaml_text, const std::string& display_name,
                                const std::vector<std::string>& overrides, const std::string& key);

// A key of a command-line option (--vary, --random, --param, --fold, --free) resolved against a
// rig (docs/keys.md): the key as parsed and the concrete paths it stands for, in document order
// (one for a plain key; one per element for each '*', which the options treat as a group).
struct RigKey {
  KeyPath key;
  std::vector<KeyPath> paths;
  bool group() const { return key.hasWildcard(); }
};

// Resolves `key` against the rig text after the overrides `sets` (a valid rig) by the rules a
// --set of it follows. A key that is not valid there throws RigError with the words a --set of
// it would get, after `typed`, what the user typed (the option and its value), e.g.
//   rig.yaml: --vary metronomes.*.nuu=0:1:3: metronomes.*.nuu: unknown key (did you mean 'nu'?)
RigKey resolveRigKey(const std::string& yaml_text, const std::string& display_name,
                     const std::vector<std::string>& sets, const std::string& key,
                     const std::string& typed);

// The rig's tree after the overrides, as JSON text (summary.json's `resolved_rig`): maps become
// objects (keys in document order), lists arrays, numbers JSON numbers that read back as the same
// double (%.17g), every other scalar a string, an empty value null. JSON is YAML, so the text is a
// rig file that runs as is. A rig without a `name` key gets the name it had here (the stem of
// display_name) as its first key, so the text names the same rig wherever it is saved. Throws
// RigError for an invalid rig, like loadRigText (a network's tree, `platforms:`, is checked
// against the schema only: its own loader, yaml/network_loader.h, checks the rest).
// `already_loaded`: the caller has loaded this text with these overrides by loadRigText (the
// rig is valid), which is then not done a second time.
std::string resolvedRigJson(const std::string& yaml_text, const std::string& display_name,
                            const std::vector<std::string>& overrides, bool already_loaded = false);

// The built-in default rig (SPEC section 2, the paper's experiment): the text of
// yaml/rigs/experiment.yaml.
std::string defaultRigYaml();

// loadRigText(defaultRigYaml(), "<default rig>", overrides, options)
Rig defaultRig(const std::vector<std::string>& overrides = {}, const LoadOptions& options = {});

}  // namespace metrosync
