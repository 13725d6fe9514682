// Rig files (SPEC section 1): YAML in either units, `--set key.path=value` overrides, validation
// with file:line:col messages, and the built-in default rig. The only public face of yaml/; no
// yaml-cpp type crosses it.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/rig.h"

namespace metrosync {

// A rig that cannot be loaded: unreadable file, YAML syntax, unknown key, wrong type, missing key,
// value out of range, bad --set. what() is ready to print as is, e.g.
//   rig.yaml:12:15: metronomes.1.pendulum.mass = -0.02: must be > 0
//   rig.yaml: --set platform.friction.mu=-1: platform.friction.mu = -1: must be >= 0
// (line and column 1-based; list indices 0-based, as in --set).
struct RigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Reads a rig file, applies the overrides in order ("key.path=value", the value parsed as YAML),
// validates everything and converts it to a Rig (a scaled rig becomes its equivalent physical
// system, see rigFromScaled). rig.name is the `name` key, else the file's stem.
Rig loadRigFile(const std::string& path, const std::vector<std::string>& overrides = {});

// The same for YAML text; display_name stands for the file in messages (and gives the name).
Rig loadRigText(const std::string& yaml_text, const std::string& display_name,
                const std::vector<std::string>& overrides = {});

// The number at `key` (a --set path) in the rig after the overrides, e.g. for the value a
// continuation starts from; nullopt when the key is absent (its default applies). Throws RigError
// for an invalid rig or a value there that is not a number.
std::optional<double> rigNumber(const std::string& yaml_text, const std::string& display_name,
                                const std::vector<std::string>& overrides, const std::string& key);

// The built-in default rig (SPEC section 2, the paper's experiment): the text of
// yaml/rigs/experiment.yaml.
std::string defaultRigYaml();

// loadRigText(defaultRigYaml(), "<default rig>", overrides)
Rig defaultRig(const std::vector<std::string>& overrides = {});

}  // namespace metrosync
